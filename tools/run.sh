#!/bin/sh
# run.sh BUILD TABLES_DIR - what `make run` does after building: bake the default tables if they
# are absent (or stale), then render: fullscreen on a KMS display when one is connected, else a
# short looping animation to PNG frames through EGL surfaceless.
set -eu
build=$1; tables=$2
bake="$build/swell-bake"; swell="$build/swell"

if ! "$bake" inspect "$tables" >/dev/null 2>&1; then
    echo "swell: baking the default sea state into $tables"
    "$bake" --preset default --out "$tables" --report "$tables.json"
fi
"$bake" inspect "$tables"

if [ ! -x "$swell" ]; then
    echo "swell: the renderer is not built; tables are ready in $tables"
    exit 0
fi

frames_dir=build/frames
mkdir -p "$frames_dir"
# --platform auto: KMS when a display is connected (fullscreen until Esc/q or Ctrl-C),
# otherwise surfaceless PNG frames.
"$swell" --platform auto --tables "$tables" --size 1280x720 --frames 48 --fps 12 \
    --path surface --out "$frames_dir/frame%04d.png"
