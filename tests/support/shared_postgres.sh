#!/usr/bin/env bash
# The one PostgreSQL server of a ctest run (the fixture tests postgres.start and postgres.stop):
# every test of the PostgreSQL store then makes databases of its own on it instead of running
# initdb and a server per test process (tests/support/postgres_process.h, shared_postgres).
#
#   shared_postgres.sh start NAME  initdb in DIR/data, a server on a free 127.0.0.1 port (in DIR/port)
#   shared_postgres.sh stop NAME   a fast shutdown, then DIR is removed
#
# DIR is NAME in the temporary directory ($TMPDIR, else /tmp), as the tests resolve it
# (std::filesystem::temp_directory_path).
#
# As for PostgresProcess: trust authentication for the user soiq, no fsync, listening on loopback
# only with its socket in DIR; as root, the server runs as the `postgres` user Debian creates.
set -euo pipefail
action=${1:?usage: shared_postgres.sh start|stop NAME}
name=${2:?usage: shared_postgres.sh start|stop NAME}
dir=${TMPDIR:-/tmp}/$name

bin=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -1)
if [ -z "$bin" ] || [ ! -x "$bin/postgres" ]; then
  echo "not installed: no /usr/lib/postgresql/*/bin/postgres (Debian package postgresql-15)" >&2
  exit 1
fi
as_server=()
[ "$(id -u)" = 0 ] && as_server=(runuser -u postgres --)

stop() {
  if [ -f "$dir/data/postmaster.pid" ]; then
    "${as_server[@]}" "$bin/pg_ctl" -D "$dir/data" -m fast -w -t 60 stop >/dev/null 2>&1 ||
      "${as_server[@]}" "$bin/pg_ctl" -D "$dir/data" -m immediate -w stop >/dev/null 2>&1 || true
  fi
  rm -rf "$dir"
}

case $action in
  stop)
    stop
    ;;
  start)
    stop  # what an interrupted run left
    mkdir -p "$dir"
    [ ${#as_server[@]} -gt 0 ] && chown postgres: "$dir"
    "${as_server[@]}" "$bin/initdb" -D "$dir/data" -U soiq -A trust -E UTF8 --locale=C --no-sync >"$dir/start.log" 2>&1 ||
      { cat "$dir/start.log" >&2; exit 1; }
    # Two tests at a time, each with a soiqd or three and their pools: more than the default 100.
    for attempt in 1 2 3; do  # the port can be taken between the probe and the server's bind
      port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
      if "${as_server[@]}" "$bin/pg_ctl" -D "$dir/data" -l "$dir/postgres.log" -w -t 60 \
        -o "-p $port -k $dir -c listen_addresses=127.0.0.1 -c max_connections=400 -c fsync=off -c synchronous_commit=off -c full_page_writes=off" \
        start >>"$dir/start.log" 2>&1; then
        echo "$port" >"$dir/port"
        exit 0
      fi
    done
    cat "$dir/start.log" "$dir/postgres.log" >&2
    exit 1
    ;;
  *)
    echo "usage: shared_postgres.sh start|stop NAME" >&2
    exit 2
    ;;
esac
