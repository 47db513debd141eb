#!/bin/sh
# mesa-shim.sh - Mesa's own drivers for the target GPUs, runnable without the hardware through
# Mesa's noop drm-shim (issue 15): lima (Mali-400/450), vc4 (VideoCore IV), v3d (VideoCore VI),
# panfrost (Mali-G31/T860...), freedreno (Adreno), etnaviv (Vivante), built from Debian's mesa
# source package, the version Debian ships on this machine, with the project's patches in
# tools/mesa-patches/.
#
# Prints the install prefix on stdout (lib/, lib/dri/, lib/lib*_noop_drm_shim.so). The build
# is cached in $SWELL_MESA_CACHE (default /var/cache/swell/mesa), outside the clone, keyed by
# the source version and a hash of this script and the patches: it is rebuilt only when one of
# them changes (about 26 CPU-minutes). Needs root the first time (apt-get: the deb-src lines
# for the machine's own archive, the build dependencies).
#
# Why a build without NDEBUG: vc4, freedreno and etnaviv print their shader statistics only
# then (with MESA_DEBUG=context).
set -eu

here=$(cd "$(dirname "$0")" && pwd)
cache=${SWELL_MESA_CACHE:-/var/cache/swell/mesa}
log() { echo "mesa-shim: $*" >&2; }
die() { log "$*"; exit 1; }

# meson and Mesa's generators need Debian's python3 with mako, not another one first on PATH
PATH=/usr/bin:/bin:/usr/sbin:/sbin
export PATH

need_pkgs="meson ninja-build python3-mako bison flex libexpat1-dev zlib1g-dev libelf-dev \
pkg-config dpkg-dev libdrm-dev"
missing=""
for p in $need_pkgs; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
        missing="$missing $p"
done

src_list=/etc/apt/sources.list.d/swell-deb-src.sources
have_src() { apt-cache showsrc mesa 2>/dev/null | grep -q '^Version:'; }
if [ -n "$missing" ] || ! have_src; then
    [ "$(id -u)" = 0 ] || die "needs root once: to install$missing and add deb-src lines ($src_list)"
    if ! have_src; then
        # the same archives as the machine's deb lines, as deb-src
        log "adding deb-src lines: $src_list"
        cat > "$src_list" <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb-src
URIs: http://deb.debian.org/debian-security
Suites: bookworm-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
    fi
    apt-get update -qq >&2 || die "apt-get update failed"
    if [ -n "$missing" ]; then
        log "installing$missing"
        # shellcheck disable=SC2086
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $missing >&2 ||
            die "apt-get install$missing failed"
    fi
    have_src || die "no source package for mesa after adding $src_list"
fi

# the version of the mesa Debian would install here (its source package's)
version=$(apt-cache policy libgl1-mesa-dri 2>/dev/null | sed -n 's/^ *Candidate: *//p')
[ -n "$version" ] && [ "$version" != "(none)" ] ||
    version=$(apt-cache showsrc mesa | sed -n 's/^Version: *//p' | head -n 1)
[ -n "$version" ] || die "cannot tell which mesa version Debian ships"

options="-Dbuildtype=debugoptimized -Db_ndebug=false -Dplatforms= \
-Dgallium-drivers=lima,vc4,v3d,panfrost,freedreno,etnaviv,kmsro -Dvulkan-drivers= \
-Dtools=drm-shim -Dllvm=disabled -Dglx=disabled -Dgles1=disabled -Dgles2=enabled \
-Degl=enabled -Dgbm=enabled -Dglvnd=false -Dshared-glapi=enabled -Dopengl=true \
-Dvalgrind=disabled -Dlibunwind=disabled -Dzstd=disabled -Dgallium-vdpau=disabled \
-Dgallium-va=disabled -Dgallium-xa=disabled -Dgallium-omx=disabled -Dgallium-nine=false \
-Dgallium-opencl=disabled -Dlmsensors=disabled -Dbuild-tests=false"

patches=$(ls "$here"/mesa-patches/*.patch 2>/dev/null || true)
# shellcheck disable=SC2086
key=$(printf '%s\n%s\n' "$version" "$options" | cat - "$0" $patches | sha256sum | cut -c1-16)
dir="$cache/${version}-$key"
if [ -f "$dir/done" ]; then
    echo "$dir/install"
    exit 0
fi

log "building mesa $version ($key) into $dir: about 26 CPU-minutes"
rm -rf "$dir"
mkdir -p "$dir/src"
(cd "$dir/src" && apt-get source -qq "mesa=$version" >&2) ||
    die "apt-get source mesa=$version failed"
tree=$(find "$dir/src" -mindepth 1 -maxdepth 1 -type d -name 'mesa-*' | head -n 1)
[ -n "$tree" ] || die "no source tree in $dir/src"
for p in $patches; do
    log "patch $(basename "$p")"
    patch -d "$tree" -p1 --forward --quiet < "$p" || die "patch $p does not apply to $version"
done
# shellcheck disable=SC2086
(cd "$tree" && meson setup "$dir/build" --prefix "$dir/install" $options > "$dir/setup.log" 2>&1) ||
    die "meson setup failed: $dir/setup.log"
jobs=$(nproc 2>/dev/null || echo 2)
ninja -C "$dir/build" -j "$jobs" install > "$dir/build.log" 2>&1 ||
    die "ninja failed: tail of $dir/build.log:
$(tail -n 20 "$dir/build.log")"
rm -rf "$dir/build" "$dir/src"
touch "$dir/done"
echo "$dir/install"
