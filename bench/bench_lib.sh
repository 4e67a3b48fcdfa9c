# bench_lib.sh — what the benchmark scripts share: building the benchmark programs,
# the load average and the machine line of a report. Sourced by run_*.sh, which set
# ROOT, BUILD_DIR and WORK (a scratch directory) and define log() first.

load_average() { cut -d' ' -f1-3 /proc/loadavg; }

# Builds the named targets (Release) in $BUILD_DIR; the build log only on failure.
# NO_BUILD=1 uses the programs already there (a tree built elsewhere and carried to
# the machine, whose paths may differ: bench/gpu_check.sh), failing if one is missing.
build_targets() {
    if [ "${NO_BUILD:-0}" = 1 ]; then
        local program
        for program in "$@"; do
            [ -x "$BUILD_DIR/bin/$program" ] || { log "NO_BUILD=1 but $BUILD_DIR/bin/$program is missing"; exit 1; }
        done
        return 0
    fi
    log "building $* in $BUILD_DIR"
    cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >"$WORK/cmake.log" 2>&1 ||
        { cat "$WORK/cmake.log" >&2; exit 1; }
    local target
    for target in "$@"; do
        cmake --build "$BUILD_DIR" --target "$target" -j2 >>"$WORK/cmake.log" 2>&1 ||
            { cat "$WORK/cmake.log" >&2; exit 1; }
    done
}

# "- machine: CPU, N cores, M GiB, OS" for a report's header.
machine_line() {
    local cpu
    cpu=$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo)
    echo "- machine: $cpu, $(nproc) cores, $(awk '/MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo)," \
         "$(. /etc/os-release && echo "$PRETTY_NAME")"
}

git_revision() { git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?'; }

# A particle count as the benchmarks read it (16k, 1m, 4096) in particles.
particle_count() {
    local value=${1%[kKmM]}
    case $1 in
        *[kK]) echo $((value * 1024)) ;;
        *[mM]) echo $((value * 1024 * 1024)) ;;
        *) echo "$value" ;;
    esac
}
