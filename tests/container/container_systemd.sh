#!/usr/bin/env bash
# container.systemd: deploy/systemd's units under a real systemd, booted as
# PID 1 in a privileged container built on the runtime image (the .deb
# installed the units): /etc/fluidcast/token written, `systemctl start
# fluidcastd.socket`, then the fluidcast CLI renders the analytic ball over TCP
# (127.0.0.1:7450) and over the Unix socket (/run/fluidcastd.sock), which
# starts fluidcastd.service by socket activation (Type=notify: active only
# after READY=1); it runs as a dynamic user; `systemctl stop` ends it cleanly
# (Result=success, ExecMainStatus=0, the SIGTERM in its journal); the
# shaders it compiled stay in its CacheDirectory, where a restart finds them.
# The container has a network namespace of its own (--network none): port
# 7450 there is nobody else's.
#   usage: container_systemd.sh SOURCE_DIR BUILD_DIR WORK_DIR BALL_TOOL
source "$(dirname "$0")/lib.sh"
[ $# -eq 4 ] || fail "usage: $0 SOURCE_DIR BUILD_DIR WORK_DIR BALL_TOOL"
SRC=$1 BUILD=$2 WORK=$3 BALL=$4
require_engine
image_names "$BUILD"
SYSTEMD_IMAGE=${RUNTIME_IMAGE/fluidcast-test:/fluidcast-test-systemd:}
OUT=$WORK/systemd
rm -rf "$OUT"
mkdir -p "$OUT"

step "build $SYSTEMD_IMAGE (systemd on $RUNTIME_IMAGE)"
DOCKER_BUILDKIT=${DOCKER_BUILDKIT:-1} "$DOCKER" build --network host -f "$(dirname "$0")/systemd.Containerfile" \
    --build-arg RUNTIME="$RUNTIME_IMAGE" -t "$SYSTEMD_IMAGE" "$OUT" > "$OUT/build.log" 2>&1 ||
    { tail -30 "$OUT/build.log"; fail "docker build of the systemd image failed"; }

# --privileged asks for every capability; where this machine's bounding set
# lacks some (here CAP_SYS_RESOURCE), runc cannot grant them and the container
# does not start: then the same privileges by name, less the missing ones.
# Both ways systemd gets the cgroup tree writable, in the host's namespace.
CAP_NAMES=(CHOWN DAC_OVERRIDE DAC_READ_SEARCH FOWNER FSETID KILL SETGID SETUID SETPCAP LINUX_IMMUTABLE
           NET_BIND_SERVICE NET_BROADCAST NET_ADMIN NET_RAW IPC_LOCK IPC_OWNER SYS_MODULE SYS_RAWIO SYS_CHROOT
           SYS_PTRACE SYS_PACCT SYS_ADMIN SYS_BOOT SYS_NICE SYS_RESOURCE SYS_TIME SYS_TTY_CONFIG MKNOD LEASE
           AUDIT_WRITE AUDIT_CONTROL SETFCAP MAC_OVERRIDE MAC_ADMIN SYSLOG WAKE_ALARM BLOCK_SUSPEND AUDIT_READ
           PERFMON BPF CHECKPOINT_RESTORE)
have=$((16#$(awk '/^CapBnd/ {print $2}' /proc/self/status)))
missing=()
for i in $(seq 0 "$(cat /proc/sys/kernel/cap_last_cap)"); do
    (( (have >> i) & 1 )) || missing+=("${CAP_NAMES[$i]:-$i}")
done
if [ ${#missing[@]} -eq 0 ]; then
    PRIV=(--privileged)
else
    echo "note: CAP_${missing[*]} not in this machine's bounding set: --privileged less that, by name"
    PRIV=(--cap-add ALL)
    for c in "${missing[@]}"; do PRIV+=(--cap-drop "$c"); done
    PRIV+=(--security-opt seccomp=unconfined --security-opt apparmor=unconfined --security-opt systempaths=unconfined
           --device-cgroup-rule "a *:* rwm")
fi
PRIV+=(--cgroupns host -v /sys/fs/cgroup:/sys/fs/cgroup:rw)

NAME=fc-test-systemd-$$
CONTAINERS+=("$NAME")
step "boot systemd: docker run ${PRIV[*]} --network none $SYSTEMD_IMAGE"
"$DOCKER" run -d --name "$NAME" "${PRIV[@]}" --network none --tmpfs /run --tmpfs /run/lock --tmpfs /tmp \
    "$SYSTEMD_IMAGE" > /dev/null
in_c() { "$DOCKER" exec "$NAME" "$@"; }
state=""
for _ in $(seq 1 120); do
    state=$(in_c systemctl is-system-running 2> /dev/null || true)
    case $state in running | degraded) break ;; esac
    sleep 0.5
done
echo "system: $state"
case $state in
    running) ;;
    degraded) in_c systemctl --failed --no-legend; fail "systemd booted degraded" ;;
    *) "$DOCKER" logs "$NAME" 2>&1 | tail -20; fail "systemd did not finish booting within 60 s: '$state'" ;;
esac
[ "$(in_c cat /proc/1/comm)" = systemd ] || fail "PID 1 is not systemd"

step "the units the package installed"
in_c systemctl cat fluidcastd.socket fluidcastd.service > "$OUT/units.txt"
matches -E '^ExecStart=/usr(/local)?/bin/fluidcastd ' "$OUT/units.txt" || fail "fluidcastd.service: $(grep ExecStart "$OUT/units.txt")"
matches -x 'ListenStream=127.0.0.1:7450' "$OUT/units.txt" || fail "fluidcastd.socket does not listen on 127.0.0.1:7450"
matches -x 'ListenStream=/run/fluidcastd.sock' "$OUT/units.txt" || fail "fluidcastd.socket has no /run/fluidcastd.sock"
matches -x 'Type=notify' "$OUT/units.txt" || fail "fluidcastd.service is not Type=notify"

# systemd makes / a shared mount at boot on a real machine but leaves that to
# the container manager inside a container, and docker keeps it a slave: then
# the credentials ramfs systemd mounts for LoadCredential= in a child
# namespace never appears in the service's view, and the token stays
# unreadable (Permission denied). Make / shared as systemd would on a host.
in_c mount --make-rshared /

step "the token, then systemctl start fluidcastd.socket"
TOKEN=$(od -An -tx1 -N16 /dev/urandom | tr -d ' \n')
in_c sh -c "install -d -m 0755 /etc/fluidcast && umask 077 && echo $TOKEN > /etc/fluidcast/token"
in_c systemctl start fluidcastd.socket
[ "$(in_c systemctl is-active fluidcastd.socket)" = active ] || fail "fluidcastd.socket is not active"
[ "$(in_c systemctl is-active fluidcastd.service || true)" = inactive ] ||
    fail "fluidcastd.service runs before anybody connected"

step "render over TCP and over the Unix socket (socket activation starts the service)"
"$BALL" write "$OUT"
# Not /tmp: docker cp writes the container's own files, under the tmpfs mounted there.
in_c mkdir -p /srv/fc
"$DOCKER" cp "$OUT/ball.f32" "$NAME:/srv/fc/ball.f32"
"$DOCKER" cp "$OUT/corners.f32" "$NAME:/srv/fc/corners.f32"
# The first render waits for the service's start, which compiles every shader
# (no cache yet): about 6 s on llvmpipe on 2 idle cores, beyond the CLI's
# default 10 s to the WELCOME while the rest of the suite loads the machine.
render() {  # SERVER INPUT OUTPUT
    in_c env FLUIDCAST_TOKEN="$TOKEN" fluidcast snapshot "/srv/fc/$2" -o "/srv/fc/$3" --server "$1" --size 160x120 \
        --eye 0,-4,0 --target 0,0,0 --radius 0.05 --absorption "$("$BALL" absorption)" --connect-timeout 60
    "$DOCKER" cp "$NAME:/srv/fc/$3" "$OUT/$3"
}
render 127.0.0.1:7450 ball.f32 tcp.png || fail "no render over TCP"
render unix:/run/fluidcastd.sock ball.f32 unix.png || fail "no render over the Unix socket"
render unix:/run/fluidcastd.sock corners.f32 empty.png || fail "no render of the empty scene"
"$BALL" check "$OUT/tcp.png" "$OUT/empty.png" || fail "the TCP render does not show the ball"
"$BALL" check "$OUT/unix.png" "$OUT/empty.png" || fail "the Unix-socket render does not show the ball"
# Without the token the daemon refuses (the unit's --token-file is in force).
if in_c fluidcast info --server 127.0.0.1:7450 > "$OUT/no-token.txt" 2>&1; then
    fail "fluidcast info without the token was answered"
fi

step "the service: started by the socket, ready, a dynamic user"
show() { in_c systemctl show -p "$1" --value fluidcastd.service; }
[ "$(show ActiveState)" = active ] || fail "fluidcastd.service: $(show ActiveState)"
MAIN=$(show MainPID)
[ "$MAIN" -gt 0 ] || fail "no MainPID"
uid=$(in_c stat -c %u "/proc/$MAIN")
echo "MainPID $MAIN, uid $uid, status: $(show StatusText)"
# DynamicUser=yes: a uid systemd allocates from 61184-65519, not a user of the image.
[ "$uid" -ge 61184 ] && [ "$uid" -le 65519 ] || fail "fluidcastd runs as uid $uid, not a dynamic user"
show StatusText | matches "^serving on 127.0.0.1:7450, unix:/run/fluidcastd.sock" ||
    fail "STATUS= (sd_notify): $(show StatusText)"
[ "$(show NRestarts)" = 0 ] || fail "fluidcastd.service restarted $(show NRestarts) times"
in_c journalctl -u fluidcastd.service --no-pager -o cat > "$OUT/journal.txt" || true
matches -i "socket activation" "$OUT/journal.txt" || fail "the journal does not say fluidcastd took the sockets: $(tail -5 "$OUT/journal.txt")"

step "systemctl stop: a clean exit"
in_c systemctl stop fluidcastd.service fluidcastd.socket
in_c journalctl -u fluidcastd.service --no-pager -o cat > "$OUT/journal.txt" || true
tail -5 "$OUT/journal.txt"
echo "$(show Result) $(show ExecMainCode) $(show ExecMainStatus) $(show ActiveState)"
[ "$(show Result)" = success ] || fail "Result=$(show Result)"
[ "$(show ExecMainStatus)" = 0 ] || fail "ExecMainStatus=$(show ExecMainStatus)"
[ "$(show ActiveState)" = inactive ] || fail "ActiveState=$(show ActiveState)"
matches "SIGTERM received: stopping" "$OUT/journal.txt" || fail "the journal lacks the SIGTERM"

# The GL driver (Mesa here) keeps the shaders it compiled in the unit's
# CacheDirectory: the dynamic user's home is read-only, so without it every
# start compiled every shader again. A restart that renders the same image
# finds them there: it adds a few entries (4-5 of about 125 here, and the
# same outside systemd), not the hundred or so a start without them writes.
step "the shader cache: kept in /var/cache/fluidcastd, found there by a restart"
cache_entries() { in_c find -L /var/cache/fluidcastd -type f | wc -l; }
first=$(cache_entries)
[ "$first" -gt 0 ] || fail "no compiled shaders under /var/cache/fluidcastd (MESA_SHADER_CACHE_DIR)"
[ "$(in_c stat -L -c %u /var/cache/fluidcastd)" = "$uid" ] || fail "/var/cache/fluidcastd is not the dynamic user's"
in_c systemctl start fluidcastd.socket
render 127.0.0.1:7450 ball.f32 restarted.png || fail "no render after the restart"
"$BALL" check "$OUT/restarted.png" "$OUT/empty.png" || fail "the render after the restart does not show the ball"
in_c systemctl stop fluidcastd.service fluidcastd.socket
again=$(cache_entries)
echo "cache entries after the first start: $first, after the restart: $again"
[ $((again - first)) -lt $((first / 4)) ] ||
    fail "the restart compiled its shaders again: $first cache entries, then $again"
echo "PASS"
