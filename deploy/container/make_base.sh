#!/usr/bin/env bash
# The base image, made here without any registry: debootstrap a minimal
# Debian 12 (bookworm, --variant=minbase) from the mirror apt on this machine
# uses, tar it, and import the tar as an image.
#
#   deploy/container/make_base.sh CACHE_DIR [TAG]      (TAG default fluidcast-base:bookworm)
#
# The tar is kept as CACHE_DIR/bookworm-minbase.tar: a rerun imports it again
# in seconds instead of debootstrapping (about 2 minutes), and when the engine
# already has TAG nothing is done at all. Delete the tar to make a fresh one.
# Needs root, debootstrap and a running engine ($FC_DOCKER, default docker; see
# engine.sh). MIRROR=http://... and SECURITY=http://... override the mirrors.
set -euo pipefail
[ $# -ge 1 ] && [ $# -le 2 ] || { echo "usage: $0 CACHE_DIR [TAG]" >&2; exit 2; }
CACHE=$1 TAG=${2:-fluidcast-base:bookworm}
DOCKER=${FC_DOCKER:-docker}
SUITE=bookworm

# The Debian mirror apt's own sources name for SUITE (deb822 or one-line
# format); host_mirror -security gives the security archive's.
host_mirror() {
    local kind=${1:-} uri
    uri=$(grep -hs -A2 '^URIs:' /etc/apt/sources.list.d/*.sources |
          awk '/^URIs:/ {u = $2} /^Suites:/ && u != "" {print u, $2; u = ""}' |
          awk -v s="bookworm$kind" '$2 == s {print $1; exit}')
    [ -n "$uri" ] || uri=$(grep -hs '^deb ' /etc/apt/sources.list /etc/apt/sources.list.d/*.list |
                           awk -v s="bookworm$kind" '$3 == s {print $2; exit}')
    if [ -z "$uri" ]; then
        if [ -n "$kind" ]; then uri=http://deb.debian.org/debian-security; else uri=http://deb.debian.org/debian; fi
    fi
    echo "$uri"
}

if "$DOCKER" image inspect "$TAG" > /dev/null 2>&1; then
    echo "base: $TAG is already in the engine"
    exit 0
fi
mkdir -p "$CACHE"
TAR=$CACHE/$SUITE-minbase.tar
if [ ! -s "$TAR" ]; then
    MIRROR=${MIRROR:-$(host_mirror)}
    SECURITY=${SECURITY:-$(host_mirror -security)}
    ROOT=$CACHE/rootfs
    rm -rf "$ROOT"
    echo "base: debootstrap --variant=minbase $SUITE from $MIRROR"
    debootstrap --variant=minbase "$SUITE" "$ROOT" "$MIRROR" > "$CACHE/debootstrap.log" 2>&1 ||
        { tail -20 "$CACHE/debootstrap.log" >&2; echo "base: debootstrap failed" >&2; exit 1; }
    # The suites this machine installs from: the point release's updates and security fixes too.
    cat > "$ROOT/etc/apt/sources.list" <<EOF
deb $MIRROR $SUITE main
deb $MIRROR $SUITE-updates main
deb $SECURITY $SUITE-security main
EOF
    # As Debian's own images: dpkg without fsync (an image layer is written once;
    # the unpacking of a few hundred packages goes several times faster), and no
    # documentation, manual pages or translations unpacked (debian:bookworm-slim).
    echo force-unsafe-io > "$ROOT/etc/dpkg/dpkg.cfg.d/docker-apt-speedup"
    printf '%s\n' 'path-exclude /usr/share/doc/*' 'path-include /usr/share/doc/*/copyright' \
        'path-exclude /usr/share/man/*' 'path-exclude /usr/share/info/*' 'path-exclude /usr/share/locale/*' \
        'path-include /usr/share/locale/locale.alias' > "$ROOT/etc/dpkg/dpkg.cfg.d/docker-slim"
    # An image carries no downloaded packages or package lists (as Debian's own images).
    rm -rf "$ROOT"/var/cache/apt/archives/*.deb "$ROOT"/var/lib/apt/lists/* "$ROOT"/var/log/*.log
    tar -C "$ROOT" --numeric-owner -cf "$TAR.part" .
    mv "$TAR.part" "$TAR"
    rm -rf "$ROOT"
fi
echo "base: docker import $TAR $TAG"
"$DOCKER" import -c 'CMD ["/bin/bash"]' -c 'ENV LANG=C.UTF-8' "$TAR" "$TAG" > /dev/null
"$DOCKER" run --rm --network host "$TAG" sh -c '. /etc/os-release && echo "base: $PRETTY_NAME"'
