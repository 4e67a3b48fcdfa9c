#!/usr/bin/env bash
# Quick start, second command: set up, build, and run the whole test suite;
# then the same suite built with AddressSanitizer and UndefinedBehaviorSanitizer
# (build-asan), where any report fails its test. The fuzzing test is left out
# of that second run: its targets are sanitized builds of their own.
set -euo pipefail
cd "$(dirname "$0")/.."
deploy/setup.sh
deploy/build.sh
status=0

# Services the deploy tests need, started here and stopped by process id on exit:
# a one-host Slurm cluster (munged, slurmctld, slurmd) in a directory of its own,
# which tests/slurm finds through SLURM_CONF. Without it they skip, saying so;
# in CI (CI=true) a cluster that does not start fails the run.
slurm_dir=$(mktemp -d /tmp/fc-slurm-cluster-XXXXXX)
slurm_cluster=$PWD/deploy/slurm/test-cluster.sh
# The container tests' engine (deploy/container/engine.sh), below; both stopped on exit.
ENGINE_RUN=""
stop_engine() { [ -z "$ENGINE_RUN" ] || deploy/container/engine.sh stop "$ENGINE_RUN" || true; ENGINE_RUN=""; }
trap 'stop_engine; "$slurm_cluster" stop "$slurm_dir"; rm -rf "$slurm_dir"' EXIT
if "$slurm_cluster" start "$slurm_dir"; then
  export SLURM_CONF=$slurm_dir/slurm.conf
else
  echo "test: the Slurm test cluster did not start (logs in $slurm_dir/log); deploy.slurm is skipped" >&2
  if [ "${CI:-}" = true ]; then status=1; fi
fi

# The container tests' engine (deploy/container/engine.sh): Debian's dockerd on a
# socket of its own, its images kept in build/container/engine for reruns;
# stopped by its PID after the suite, whatever the suite's result.
if engine=$(deploy/container/engine.sh start build/container/engine); then
    eval "$engine"
    ENGINE_RUN=$FC_ENGINE_RUN
else
    echo "test: the container engine did not start: the container tests will fail (see above)"
fi
# CI runs the container tests: a missing engine fails them instead of skipping them.
export FC_CONTAINER_REQUIRED=1
(cd build && ctest --output-on-failure -j "$(nproc)" --timeout 900) || status=1
stop_engine

echo "test: sanitizer suite (build-asan, FC_SANITIZE=address,undefined)"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFC_SANITIZE=address,undefined > /dev/null
cmake --build build-asan -j "$(nproc)"
# Leaks inside third-party libraries are not ours: tests/sanitizer/lsan.supp names each and why.
export ASAN_OPTIONS=detect_leaks=1
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1
# soak.renders bounds the daemon's RSS growth, which under AddressSanitizer
# measures its quarantine of freed memory (about 120 MB), not the daemon.
(cd build-asan && ctest --output-on-failure -j "$(nproc)" --timeout 1800 -LE fuzz -E '^soak\.renders$') || status=1
exit $status
