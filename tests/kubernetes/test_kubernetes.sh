#!/usr/bin/env bash
# test_kubernetes.sh — deploy/kubernetes validated offline: every manifest
# against the Kubernetes JSON schemas (npm's kubernetes-models, installed into
# build/npm by deploy/setup.sh) and against what fluidcastd needs
# (deploy/kubernetes/validate.cjs), with the daemon's drain time read from its
# source. Then deliberately broken copies, each of which must be refused with
# the reason named: a schema error (a port given as text, a missing selector)
# and each of the fluidcastd checks.
#
# Usage: test_kubernetes.sh SOURCE_DIR NODE_MODULES_DIR. Exit 77 (skip) when
# node or the npm packages are missing, saying how to get them.
set -uo pipefail

source=$1 modules=$2
skip() { echo "SKIP: $*"; exit 77; }
command -v node > /dev/null || skip "node is not installed (deploy/setup.sh installs nodejs)"
[[ -f $modules/kubernetes-models/package.json && -f $modules/yaml/package.json ]] ||
    skip "kubernetes-models/yaml not in $modules (deploy/setup.sh installs them: npm ci in build/npm)"

manifests=$source/deploy/kubernetes
validator=$manifests/validate.cjs
drain_ms=$(sed -n 's/^ *SHUTDOWN_DRAIN_MS = \([0-9]*\).*/\1/p' "$source/server/daemon/net/event_loop.c")
[[ $drain_ms =~ ^[0-9]+$ ]] || { echo "FAIL: SHUTDOWN_DRAIN_MS not found in server/daemon/net/event_loop.c"; exit 1; }

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# validate.cjs wants a volume at the image's shader cache folder.
grep -q '^ENV MESA_SHADER_CACHE_DIR=/var/cache/fluidcast ' "$source/deploy/container/Containerfile" ||
    fail "deploy/container/Containerfile does not set MESA_SHADER_CACHE_DIR=/var/cache/fluidcast (validate.cjs)"
work=$(mktemp -d /tmp/fc-k8s-XXXXXX)
trap 'rm -rf "$work"' EXIT

validate() { node "$validator" "$modules" "$drain_ms" "$@"; }

out=$(validate "$manifests"/*.yaml 2>&1) || fail "the manifests do not validate:"$'\n'"$out"
echo "$out"
[[ $out == *"StatefulSet fluidcastd (schema apps/v1)"* && $out == *"Service fluidcastd-headless"* &&
   $out == *"Secret fluidcast-token"* && $out == *"Secret fluidcast-tls"* ]] || fail "not every manifest was checked"

# broken NAME SED_EXPRESSION FILE EXPECTED: a copy with one change must be refused, saying EXPECTED.
broken() {
    local name=$1 expression=$2 file=$3 expected=$4 copy=$work/$1
    mkdir -p "$copy"
    cp "$manifests"/*.yaml "$copy/"
    sed -i "$expression" "$copy/$file"
    if cmp -s "$manifests/$file" "$copy/$file"; then
        fail "$name: the edit changed nothing in $file"
        return
    fi
    local result status
    result=$(validate "$copy"/*.yaml 2>&1)
    status=$?
    if [[ $status -eq 0 ]]; then
        fail "$name: accepted"$'\n'"$result"
    elif [[ $result != *"$expected"* ]]; then
        fail "$name: refused, but not for \"$expected\":"$'\n'"$result"
    else
        echo "refused as expected: $name ($(grep -m1 '^FAIL' <<< "$result"))"
    fi
}

# Schema errors (kubernetes-models).
broken port-as-text 's/containerPort: 7450/containerPort: "seven-four-five-oh"/' statefulset.yaml \
    "containerPort must be integer"
broken no-selector '/^  selector:$/,/^      app.kubernetes.io\/name: fluidcastd$/d' statefulset.yaml \
    "must have required property selector"
broken bad-protocol '0,/protocol: TCP/s//protocol: QUIC/' service.yaml "protocol must be equal to one of"
broken unknown-kind 's/^kind: Secret$/kind: Sekret/' secret.yaml 'no schema for apiVersion "v1" kind "Sekret"'
# What fluidcastd needs.
broken short-grace 's/terminationGracePeriodSeconds: 30/terminationGracePeriodSeconds: 3/' statefulset.yaml \
    "is not longer than the daemon's drain"
broken readiness-on-healthz '/readinessProbe:/,/path:/s#path: /readyz#path: /healthz#' statefulset.yaml \
    "readinessProbe asks /healthz, expected /readyz"
broken probe-render-port '/livenessProbe:/,/port:/s/port: metrics/port: fluidcast/' statefulset.yaml \
    "livenessProbe probes port fluidcast"
broken no-gpu '/nvidia.com\/gpu: 1/d' statefulset.yaml "no nvidia.com/gpu limit"
broken metrics-on-loopback 's/- 0.0.0.0:9090/- 127.0.0.1:9090/' statefulset.yaml "--metrics-listen 127.0.0.1:9090"
broken token-not-mounted 's#- /run/secrets/fluidcast/token#- /etc/fluidcast/token#' statefulset.yaml \
    "lies under no volume mount"
broken secret-key 's/^  token: /  secret: /' secret.yaml 'has no key "token"'
broken no-tls '/- --tls-cert$/,/- \/run\/secrets\/fluidcast-tls\/tls.crt$/d' statefulset.yaml "no --tls-cert"
broken tls-secret-key 's/^  tls.key: /  key: /' tls-secret.yaml 'has no key "tls.key"'
broken no-token '/- --token-file/,+1d' statefulset.yaml "no --token-file"
broken srv-port-name '/name: fluidcastd-headless/,$s/- name: fluidcast$/- name: render/' service.yaml \
    'no TCP port named "fluidcast"'
broken not-headless 's/clusterIP: None/type: ClusterIP/' service.yaml "no headless Service"
broken no-shader-cache 's#mountPath: /var/cache/fluidcast#mountPath: /var/cache/elsewhere#' statefulset.yaml \
    "no volume at /var/cache/fluidcast"
broken selector-mismatch '/^  selector:$/{n;s/fluidcastd$/other/}' service.yaml "selects no fluidcastd pod"

if [[ $failures -eq 0 ]]; then
    echo "kubernetes: all checks passed"
    exit 0
fi
echo "kubernetes: $failures check(s) failed"
exit 1
