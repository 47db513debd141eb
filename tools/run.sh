#!/bin/sh
# run.sh BUILD TABLES_DIR - what `make run` does after building: bake the default tables if they
# are absent (or stale), then render: fullscreen on a KMS display when one is connected, else a
# short looping animation to PNG frames through EGL surfaceless.
set -eu
build=$1; tables=$2
bake="$build/swell-bake"; swell="$build/swell"

if ! "$bake" inspect "$tables" >/dev/null 2>&1; then
    echo "swell: baking the default sea state into $tables"
    # the report goes beside the tables; swell-bake refuses a missing folder before baking
    mkdir -p "$(dirname "$tables")"
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
# otherwise surfaceless PNG frames: 48 frames at 3 per second span the 16 s loop period, so the
# sequence loops seamlessly (frame 48 would equal frame 0).
if [ -e /dev/dri/card0 ]; then
    "$swell" --platform auto --tables "$tables"
else
    "$swell" --platform surfaceless --tables "$tables" --size 1280x720 --frames 48 --fps 3 \
        --camera 0,0,8 --pitch -8 --out "$frames_dir/frame%04d.png"
    echo "swell: wrote 48 looping frames to $frames_dir/frame0000.png .. frame0047.png"
fi
