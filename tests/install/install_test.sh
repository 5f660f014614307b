#!/usr/bin/env bash
# The install and the CMake package, as a packager and a user of the client library meet them:
# `cmake --install` into a fresh prefix puts soiq and soiqd in bin/, soiq's bash completion and the
# soiq(1) and soiqd(8) man pages under share/; a separate project finds the
# package with find_package(soiq), links soiq::client, and asks a real soiqd (the installed one,
# on a free loopback port) for its version, which must be this build's.
#   install_test.sh SOURCE_DIR BUILD_DIR [CONSUMER_LINK_FLAGS [CXX_COMPILER]]
set -euo pipefail
source_dir=$1
build=$2
link_flags=${3:-}
compiler=${4:-c++}
tmp=$(mktemp -d)
soiqd_pid=
trap '[ -n "$soiqd_pid" ] && kill "$soiqd_pid" 2>/dev/null; rm -rf "$tmp"' EXIT
fail() {
  echo "FAIL: $*"
  exit 1
}

cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" 2>&1 || fail "cmake --install: $(tail -5 "$tmp/install.log")"
for f in bin/soiq bin/soiqd include/soiq/client/soiq_client.h include/soiq/soiq/v1/soiq.grpc.pb.h \
  include/soiq/core/base/status.h lib/cmake/soiq/soiqConfig.cmake share/bash-completion/completions/soiq \
  share/man/man1/soiq.1 share/man/man8/soiqd.8; do
  [ -e "$tmp/prefix/$f" ] || fail "not installed: $f"
done

mkdir -p "$tmp/consumer"
cat >"$tmp/consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(consumer CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(soiq REQUIRED)
add_executable(consumer main.cpp)
target_link_libraries(consumer PRIVATE soiq::client)
CMAKE
cat >"$tmp/consumer/main.cpp" <<'CPP'
#include <cstdio>

#include "client/soiq_client.h"

int main(int argc, char** argv) {
  soiq::client::ClientOptions options;
  options.address = argv[1];
  auto client = soiq::client::Client::connect(options);
  if (!client.ok()) return 2;
  auto info = client->server_info();
  if (!info.ok()) {
    std::printf("%s\n", info.status().to_string().c_str());
    return 1;
  }
  std::printf("%s\n", info->version().c_str());
  return 0;
}
CPP
cmake -S "$tmp/consumer" -B "$tmp/consumer/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_EXE_LINKER_FLAGS="$link_flags" -DCMAKE_CXX_COMPILER="$compiler" >"$tmp/configure.log" 2>&1 ||
  fail "find_package(soiq): $(tail -20 "$tmp/configure.log")"
cmake --build "$tmp/consumer/build" >"$tmp/build.log" 2>&1 || fail "linking soiq::client: $(tail -20 "$tmp/build.log")"

"$tmp/prefix/bin/soiqd" --listen 127.0.0.1:0 --db "$tmp/soiq.db" --port-file "$tmp/port" --workers 1 >"$tmp/soiqd.log" 2>&1 &
soiqd_pid=$!
for _ in $(seq 1 200); do
  [ -s "$tmp/port" ] && break
  sleep 0.05
done
[ -s "$tmp/port" ] || fail "the installed soiqd did not start: $(cat "$tmp/soiqd.log")"
version=$("$tmp/consumer/build/consumer" "127.0.0.1:$(tr -d '[:space:]' <"$tmp/port")") || fail "consumer: $version"
expected=$(sed -n 's/^project(soiq VERSION \([0-9.]*\).*/\1/p' "$source_dir/CMakeLists.txt")
[ "$version" = "$expected" ] || fail "the consumer read version '$version', expected '$expected'"
echo "ok: installed, found with find_package(soiq), linked soiq::client, read version $version from soiqd"
