#!/usr/bin/env bash
# The container engine the container tests (ctest -L container) talk to:
# Debian 12's dockerd (package docker.io: dockerd, containerd, runc), started by
# hand as root, on a socket and in directories of its own, so that it neither
# needs systemd nor touches a docker.service the machine may also run.
#
#   eval "$(deploy/container/engine.sh start DATA_DIR)"   # exports DOCKER_HOST, FC_DOCKER,
#                                                        # DOCKER_BUILDKIT, FC_ENGINE_RUN
#   deploy/container/engine.sh stop "$FC_ENGINE_RUN"      # stops it by its process id
#
# DATA_DIR keeps images and build cache between runs (deploy/test.sh uses
# build/container/engine), so a rerun reuses the base image and layers.
# The engine runs with --bridge=none and no iptables rules: every build and
# container uses the host's network (--network host), which needs no NAT, and
# a second dockerd on the machine (its docker0) is left alone.
# Prints what it does on stderr; stdout is only the export lines.
set -euo pipefail

die() { echo "engine: $*" >&2; exit 1; }

start() {
    local data=$1
    command -v dockerd > /dev/null || die "no dockerd: apt-get install docker.io (deploy/setup.sh)"
    [ "$(id -u)" -eq 0 ] || die "dockerd needs root"
    mkdir -p "$data"
    data=$(cd "$data" && pwd)
    # A short path: containerd's sockets live under the exec root (108-byte limit).
    local run
    run=$(mktemp -d /tmp/fc-engine.XXXXXX)
    local sock=$run/docker.sock
    # setsid: the engine outlives the shell that started it and is stopped by PID.
    setsid dockerd --host "unix://$sock" --data-root "$data" --exec-root "$run/exec" \
        --pidfile "$run/dockerd.pid" --bridge=none --iptables=false --ip-masq=false \
        > "$run/dockerd.log" 2>&1 < /dev/null &
    local pid=$!
    echo "$pid" > "$run/pid"
    local client=docker
    # Debian's client (docker.io) builds with BuildKit without the buildx plugin,
    # skipping the Containerfile stages a build does not need.
    [ -x /usr/bin/docker ] && client=/usr/bin/docker
    for _ in $(seq 1 120); do
        if DOCKER_HOST=unix://$sock "$client" info > /dev/null 2>&1; then
            # dockerd's own record of its PID, in case setsid had to fork.
            [ -s "$run/dockerd.pid" ] && pid=$(cat "$run/dockerd.pid") && echo "$pid" > "$run/pid"
            echo "engine: dockerd $pid on $sock (data $data, log $run/dockerd.log)" >&2
            printf 'export DOCKER_HOST=%q FC_DOCKER=%q DOCKER_BUILDKIT=1 FC_ENGINE_RUN=%q\n' \
                "unix://$sock" "$client" "$run"
            return 0
        fi
        kill -0 "$pid" 2> /dev/null || { tail -20 "$run/dockerd.log" >&2; die "dockerd exited"; }
        sleep 0.5
    done
    tail -20 "$run/dockerd.log" >&2
    kill "$pid" 2> /dev/null || true
    die "dockerd did not answer within 60 s"
}

stop() {
    local run=$1
    [ -f "$run/pid" ] || die "$run/pid: no engine started there"
    local pid
    pid=$(cat "$run/pid")
    if kill -0 "$pid" 2> /dev/null; then
        # dockerd stops its containers and its containerd, then exits.
        kill -TERM "$pid"
        for _ in $(seq 1 60); do
            kill -0 "$pid" 2> /dev/null || break
            sleep 0.5
        done
        if kill -0 "$pid" 2> /dev/null; then
            echo "engine: dockerd $pid still running after 30 s: SIGKILL" >&2
            kill -KILL "$pid" 2> /dev/null || true
        fi
    fi
    echo "engine: dockerd $pid stopped" >&2
    # What dockerd leaves mounted under its exec root (the default network
    # namespace's bind mount), deepest first, before removing it.
    findmnt -rn -o TARGET | grep -F "$run/" | sort -r | while read -r m; do umount -l "$m" || true; done
    rm -rf "$run"
}

case "${1:-}" in
    start) [ $# -eq 2 ] || die "usage: $0 start DATA_DIR"; start "$2" ;;
    stop) [ $# -eq 2 ] || die "usage: $0 stop RUN_DIR"; stop "$2" ;;
    *) die "usage: $0 start DATA_DIR | stop RUN_DIR" ;;
esac
