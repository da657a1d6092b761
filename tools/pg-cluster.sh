#!/bin/sh
# A private PostgreSQL cluster for the database tests (docs/patient-library.md, "Tests"):
# Debian's postgresql package (tools/install-deps.sh), initdb into a folder of its own,
# listening on 127.0.0.1 at a free port (and on a unix socket in that folder), password
# authentication as a classroom server would use.
#
#   tools/pg-cluster.sh start DIR   creates and starts it in the empty folder DIR; prints
#                                   its URL, postgresql://palpation:PASSWORD@127.0.0.1:PORT/palpation
#                                   (the user may create databases: each test makes its own)
#   tools/pg-cluster.sh stop DIR    stops it and removes DIR (quietly when it is not running)
#
# PostgreSQL refuses to run as root: as root, the server runs as the user postgres (made
# by the package), else nobody, owning DIR. Durability is off (fsync, synchronous commit):
# the cluster lives for one test run.
set -eu
cmd=${1:-}
dir=${2:-}
if [ -z "$cmd" ] || [ -z "$dir" ]; then
  echo "usage: $0 start|stop DIR" >&2
  exit 2
fi
bin=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -n 1)
if [ -z "$bin" ] || [ ! -x "$bin/initdb" ]; then
  echo "pg-cluster: PostgreSQL is not installed (/usr/lib/postgresql/*/bin/initdb); run tools/install-deps.sh" >&2
  exit 1
fi

as_user() {
  if [ "$(id -u)" = 0 ]; then
    runuser -u "$owner" -- "$@"
  else
    "$@"
  fi
}
owner=$(id -un)
if [ "$(id -u)" = 0 ]; then
  if id postgres >/dev/null 2>&1; then owner=postgres; else owner=nobody; fi
fi

case "$cmd" in
start)
  mkdir -p "$dir"
  chmod 700 "$dir"
  if [ "$(id -u)" = 0 ]; then
    chown "$owner" "$dir"
    if ! runuser -u "$owner" -- test -x "$dir"; then
      echo "pg-cluster: $dir: the server's user $owner cannot reach it (a folder above it is private); use a folder in /tmp" >&2
      exit 1
    fi
  fi
  password=$(od -An -tx1 -N16 /dev/urandom | tr -d ' \n')
  (umask 077 && printf '%s\n' "$password" > "$dir/password")
  [ "$(id -u)" = 0 ] && chown "$owner" "$dir/password"
  if ! as_user "$bin/initdb" -D "$dir/data" -U palpation --pwfile="$dir/password" -A scram-sha-256 \
      -E UTF8 --no-locale --no-sync >"$dir/initdb.log" 2>&1; then
    cat "$dir/initdb.log" >&2
    echo "pg-cluster: initdb failed in $dir/data" >&2
    exit 1
  fi
  # A free port: try a few from a pseudo-random start; the server says when one is taken.
  port=$(( 20000 + $$ % 20000 ))
  tries=0
  while :; do
    if as_user "$bin/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w -t 60 -s start \
        -o "-c listen_addresses=127.0.0.1 -c port=$port -c unix_socket_directories=$dir -c fsync=off \
            -c synchronous_commit=off -c full_page_writes=off -c max_connections=100" >/dev/null 2>&1; then
      break
    fi
    tries=$((tries + 1))
    if [ "$tries" -ge 10 ] || ! grep -q "could not bind\|Address already in use\|could not create any TCP/IP sockets" "$dir/server.log"; then
      cat "$dir/server.log" >&2
      echo "pg-cluster: the server did not start in $dir/data" >&2
      exit 1
    fi
    port=$((port + 1 + $$ % 97))
  done
  if ! PGPASSWORD=$password as_user "$bin/createdb" -h "$dir" -p "$port" -U palpation palpation >"$dir/createdb.log" 2>&1; then
    cat "$dir/createdb.log" >&2
    as_user "$bin/pg_ctl" -D "$dir/data" -m immediate -s stop >/dev/null 2>&1 || true
    exit 1
  fi
  echo "$port" > "$dir/port"
  echo "postgresql://palpation:$password@127.0.0.1:$port/palpation"
  ;;
stop)
  if [ -d "$dir/data" ]; then
    as_user "$bin/pg_ctl" -D "$dir/data" -m immediate -s stop >/dev/null 2>&1 || true
  fi
  rm -rf "$dir"
  ;;
*)
  echo "usage: $0 start|stop DIR" >&2
  exit 2
  ;;
esac
