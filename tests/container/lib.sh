# tests/container/lib.sh — what the container tests share (sourced).
# The engine: $FC_DOCKER (default docker) with $DOCKER_HOST, as
# deploy/container/engine.sh exports them. Without a reachable engine a test
# skips (exit 77, ctest's SKIP_RETURN_CODE) saying why, unless
# FC_CONTAINER_REQUIRED=1 (deploy/test.sh, CI), where it fails.
set -euo pipefail

SKIP=77
DOCKER=${FC_DOCKER:-docker}

step() { echo "== $(date +%T) $*"; }
fail() { echo "FAIL: $*" >&2; exit 1; }
# grep -q ending a pipe early can fail it under pipefail: read everything.
matches() { grep "$@" > /dev/null; }

require_engine() {
    local why=""
    if [ "$(id -u)" -ne 0 ] && [ -z "${DOCKER_HOST:-}" ]; then
        why="not root and no DOCKER_HOST"
    elif ! command -v "$DOCKER" > /dev/null; then
        why="no container client '$DOCKER' (apt-get install docker.io)"
    elif ! "$DOCKER" info > /dev/null 2>&1; then
        why="no container engine answers at ${DOCKER_HOST:-the default socket} (start one: eval \"\$(deploy/container/engine.sh start build/container/engine)\")"
    fi
    [ -z "$why" ] && return 0
    if [ "${FC_CONTAINER_REQUIRED:-0}" = 1 ]; then
        fail "FC_CONTAINER_REQUIRED=1 but $why"
    fi
    echo "SKIP: $why"
    exit $SKIP
}

# Image names of one build tree, so two build trees sharing an engine do not
# overwrite each other's images. BUILD is the build directory.
image_names() {
    local id
    id=$(printf '%s' "$1" | sha1sum | cut -c1-8)
    BASE_IMAGE=fluidcast-test-base:bookworm
    RUNTIME_IMAGE=fluidcast-test:$id
}

# A free TCP port on loopback in 20000-60000 (the containers share the host's network).
free_port() {
    local port
    for _ in $(seq 1 50); do
        port=$((20000 + RANDOM % 40000))
        if ! (exec 3<> "/dev/tcp/127.0.0.1/$port") 2> /dev/null; then
            echo "$port"
            return 0
        fi
    done
    fail "no free port found"
}

# Waits until container NAME listens on loopback PORT; fails with its log when
# it exits first or $3 seconds pass.
wait_container_port() {
    local name=$1 port=$2 limit=$3
    for _ in $(seq 1 $((limit * 10))); do
        (exec 3<> "/dev/tcp/127.0.0.1/$port") 2> /dev/null && return 0
        if [ "$("$DOCKER" inspect -f '{{.State.Running}}' "$name" 2> /dev/null)" != true ]; then
            "$DOCKER" logs "$name" 2>&1 | tail -20
            fail "container $name exited ($("$DOCKER" inspect -f '{{.State.ExitCode}}' "$name" 2> /dev/null)) before listening on $port"
        fi
        sleep 0.1
    done
    "$DOCKER" logs "$name" 2>&1 | tail -20
    fail "container $name does not listen on $port within $limit s"
}

# Containers this test started; removed on exit whatever happened.
CONTAINERS=()
cleanup_containers() {
    for c in "${CONTAINERS[@]}"; do
        "$DOCKER" rm -f "$c" > /dev/null 2>&1 || true
    done
}
trap cleanup_containers EXIT
