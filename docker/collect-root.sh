#!/bin/bash
# Makes a directory that is a whole image's file system, for `FROM scratch`: the programs given,
# the shared libraries each loads (as ldd resolves them, the dynamic loader included), a user
# and a writable /tmp. The worker's image is this and nothing else (docs/MULTIHOST.md).
#   collect-root.sh ROOT UID NAME PROGRAM...
# A PROGRAM is a command on PATH, installed at the path it has here, or SOURCE:DESTINATION.
set -euo pipefail
root=$1 uid=$2 name=$3
shift 3

install_file() {  # SOURCE DESTINATION: the file itself, not a symbolic link to it
  mkdir -p "$root$(dirname "$2")"
  cp -L "$1" "$root$2"
}

for program in "$@"; do
  source=${program%%:*} destination=${program#*:}
  if [ "$source" = "$program" ]; then
    source=$(command -v "$program")
    destination=$source
  fi
  install_file "$source" "$destination"
  # A script loads no libraries (ldd fails on it); a program's lines read
  # "libc.so.6 => /lib/x86_64-linux-gnu/libc.so.6 (0x...)" or "/lib64/ld-linux-x86-64.so.2 (0x...)".
  libraries=$(ldd "$source" 2>/dev/null) || continue
  awk '$2 == "=>" && $3 ~ /^\// { print $3 } $1 ~ /^\// { print $1 }' <<<"$libraries" |
    while read -r library; do
      [ -e "$root$library" ] || install_file "$library" "$library"
    done
done

mkdir -p "$root/etc" "$root/tmp" "$root/home/$name"
chmod 1777 "$root/tmp"
chown "$uid:$uid" "$root/home/$name"
printf 'root:x:0:0:root:/root:/bin/bash\n%s:x:%s:%s::/home/%s:/bin/bash\n' \
  "$name" "$uid" "$uid" "$name" >"$root/etc/passwd"
printf 'root:x:0:\n%s:x:%s:\n' "$name" "$uid" >"$root/etc/group"
