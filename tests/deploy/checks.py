"""What the deploy tests share: checks that collect every failure instead of stopping at the
first, so one run lists all that a manifest or compose file gets wrong."""

FAILURES = []


def check(condition, message):
    if not condition:
        FAILURES.append(message)
