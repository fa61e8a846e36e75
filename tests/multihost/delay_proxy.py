#!/usr/bin/env python3
"""A TCP relay that adds latency and a bandwidth limit, for machines whose kernel has no tc
netem (tests/multihost/netns.py uses netem where it exists). Every byte is held back
`--delay-ms` in each direction (so a round trip gains twice that) and each direction is paced
to `--rate-mbit`, in order, like a long link. It writes its listening port to --port-file.

usage: delay_proxy.py --connect HOST:PORT --delay-ms D [--rate-mbit R] --port-file FILE
"""
import argparse
import asyncio
import json
import os
import time


async def pump(reader, writer, delay, rate_bytes):
    """Copies one direction: each chunk leaves `delay` seconds after it arrived, and no sooner
    than the link's rate allows after the chunk before it."""
    queue = asyncio.Queue()

    async def deliver():
        link_free = 0.0
        while True:
            due, data = await queue.get()
            if data is None:
                break
            if rate_bytes:
                link_free = max(link_free, due - delay) + len(data) / rate_bytes
                due = max(due, link_free + delay)
            await asyncio.sleep(max(0.0, due - time.monotonic()))
            writer.write(data)
            await writer.drain()
        writer.close()

    sender = asyncio.create_task(deliver())
    try:
        while data := await reader.read(65536):
            await queue.put((time.monotonic() + delay, data))
    except ConnectionError:
        pass
    await queue.put((0, None))
    try:
        await sender
    except ConnectionError:
        pass


async def main(args):
    host, port = args.connect.rsplit(":", 1)
    delay = args.delay_ms / 1000
    rate = args.rate_mbit * 1e6 / 8 if args.rate_mbit else 0

    async def relay(client_reader, client_writer):
        try:
            up_reader, up_writer = await asyncio.open_connection(host, int(port))
        except OSError:
            client_writer.close()
            return
        await asyncio.gather(pump(client_reader, up_writer, delay, rate),
                             pump(up_reader, client_writer, delay, rate))

    server = await asyncio.start_server(relay, "127.0.0.1", 0)
    partial = args.port_file + ".partial"
    with open(partial, "w") as f:
        json.dump({"port": server.sockets[0].getsockname()[1]}, f)
    os.rename(partial, args.port_file)
    async with server:
        await server.serve_forever()


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--connect", required=True)
    parser.add_argument("--delay-ms", type=float, required=True)
    parser.add_argument("--rate-mbit", type=float, default=0)
    parser.add_argument("--port-file", required=True)
    asyncio.run(main(parser.parse_args()))
