# Sourced by envmap's bench scripts after they set $here (this directory): the repository root,
# the build directory (the script's first argument, else build/), blender_hdr, pareto_front and gp.
root=$(cd "$here/../../.." && pwd)
build=${1:-$root/build}
# blender_hdr NAME: the path of Blender's studio-light environment NAME.exr (Debian blender-data,
# with or without a version directory), empty when it is not installed.
blender_hdr() {
    ls /usr/share/blender/*/datafiles/studiolights/world/"$1".exr \
       /usr/share/blender/datafiles/studiolights/world/"$1".exr 2>/dev/null | head -1 || true
}
# pareto_front MEAN.csv: the rows of MEAN.csv (alpha,method,ms,error,..., sorted by alpha then ms)
# that are more accurate than every faster row of the same alpha: the error-vs-ms Pareto front.
pareto_front() {
    awk -F, '{ a = $1; if (a != last) { best = 1e30; last = a } if ($4 < best) { best = $4; print $0 } }' "$1"
}
# gp WxH FONTSIZE COMMANDS: gnuplot to PNG (pngcairo when the build has it, else png)
gp() {
    gnuplot -e "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size $1 font 'sans,$2' } else { set terminal png size $1 }; set termoption noenhanced; $3"
}
