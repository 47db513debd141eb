#!/bin/sh
# pictures.sh BUILD - render the README's pictures (docs/*.png) with BUILD/swell, each scene's
# whole command listed here so a picture can be checked against the program that made it.
# Offscreen (surfaceless), 640x360, the best tier the GL context offers.
set -eu
build=${1:-build/rel}
swell="$build/swell"
[ -x "$swell" ] || { echo "pictures: $swell not built (make $swell)" >&2; exit 2; }
mkdir -p docs
shot() {   # shot NAME ARGS...
    name=$1
    shift
    echo "pictures: docs/$name.png: swell $*"
    "$swell" --platform surfaceless --size 640x360 --frames 1 --time 4 "$@" \
        --out "docs/$name.png" >/dev/null
}
shot moderate      --preset moderate --camera 0,0,12 --pitch -8 --heading 20 --sun 35,120
shot moderate_low  --preset moderate --camera 0,0,12 --pitch -8 --heading 20 --sun 35,120 --quality low
shot glint         --preset moderate --camera 0,0,8 --pitch -4 --heading 0 --sun 7,0
shot storm         --preset storm --camera 0,0,20 --pitch -14 --heading 60 --sun 40,200
shot altitude_1km  --preset moderate --path 1km --sun 30,20
shot storm_boat    --preset storm --camera 1586.8,48.1,5 --pitch -8 --heading 0 --sun 30,20 --time 0
shot altitude_10km --preset moderate --camera 0,0,10000 --pitch -4 --sun 20,30
shot nadir_3km     --preset moderate --camera 0,0,3000 --pitch -89 --sun 45,90
shot orbit         --preset moderate --path orbit --sun 30,20
shot boat          --boat 1.5,75 --preset calm --camera 0,0,3 --pitch -5 --sun 15,5 --time 3
shot wake          --boat 5,60 --preset calm --camera -20,-30,14 --pitch -16 --heading 45 --sun 40,250
