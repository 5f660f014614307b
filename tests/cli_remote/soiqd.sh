# Shared by the remote command-line tests (sourced after tests/cli/lib.sh): a real soiqd on a free
# loopback port with its own SQLite file in $tmp, stopped when the test exits.
#   start_soiqd NAME [soiqd flags...]  sets $server (127.0.0.1:PORT) and $soiqd_pid
#   stop_soiqd                         SIGTERM, then waits for it
soiqd_pids=()
trap 'for p in "${soiqd_pids[@]}"; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done; rm -rf "$tmp"' EXIT

start_soiqd() {
  local name=$1
  shift
  rm -f "$tmp/$name.port"
  "$soiqd" --listen 127.0.0.1:0 --db "$tmp/$name.db" --port-file "$tmp/$name.port" --workers 2 "$@" \
    >"$tmp/$name.log" 2>&1 &
  soiqd_pid=$!
  soiqd_pids+=("$soiqd_pid")
  for _ in $(seq 1 200); do
    [ -s "$tmp/$name.port" ] && break
    kill -0 "$soiqd_pid" 2>/dev/null || break
    sleep 0.05
  done
  if [ ! -s "$tmp/$name.port" ]; then
    echo "FAIL: soiqd did not start: $(cat "$tmp/$name.log")"
    exit 1
  fi
  server="127.0.0.1:$(tr -d '[:space:]' <"$tmp/$name.port")"
}

stop_soiqd() {
  kill "$soiqd_pid" 2>/dev/null
  wait "$soiqd_pid" 2>/dev/null
}
