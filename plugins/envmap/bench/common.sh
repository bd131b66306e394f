# Sourced by envmap's bench scripts after they set $here (this directory): the repository root,
# the build directory (the script's first argument, else build/), blender_hdr, metal_row, pareto_front,
# gp and gp_noisy.
root=$(cd "$here/../../.." && pwd)
build=${1:-$root/build}
# blender_hdr NAME: the path of Blender's studio-light environment NAME.exr (Debian blender-data,
# with or without a version directory), empty when it is not installed.
blender_hdr() {
    ls /usr/share/blender/*/datafiles/studiolights/world/"$1".exr \
       /usr/share/blender/datafiles/studiolights/world/"$1".exr 2>/dev/null | head -1 || true
}
# metal_row MAP HDR: the scene cycles.sh charts (and dots.sh crops), on stdout: a row of white metal
# spheres (GGX alpha 0.05, 0.2, 0.4, 0.7, 1, F0 = 1, radius 0.42, 1 m apart) under HDR (Blender's
# MAP.exr), environment only, seen from 9 m with a 7° field of view. Written byte for byte as
# before, so that xcheck's cached Cycles images are found.
metal_row() {
  local alphas=(0.05 0.2 0.4 0.7 1.0) names=(005 020 040 070 100) i
  { echo '{'
    echo "  \"comment\": \"Metal sphere row under Blender's $1.exr: GGX alpha 0.05, 0.2, 0.4, 0.7, 1 (white metal, F0 = 1), environment only.\","
    echo '  "plugins": ["ggx", "envmap"],'
    echo '  "cameras": [ { "name": "main", "position": [0, 0, 9], "target": [0, 0, 0], "fov_y": 7, "near": 0.5, "far": 50 } ],'
    echo "  \"environment\": { \"map\": \"$2\" },"
    echo '  "materials": ['
    for i in 0 1 2 3 4; do
      printf '    { "name": "a%s", "model": "ggx", "fresnel": "metallic-roughness", "metallic": 1, "base_color": [1, 1, 1], "alpha": %s }%s\n' \
        "${names[$i]}" "${alphas[$i]}" "$([ $i -lt 4 ] && echo ,)"
    done
    echo '  ],'
    echo '  "nodes": ['
    for i in 0 1 2 3 4; do
      printf '    { "name": "s%s", "translate": [%s, 0, 0], "mesh": { "primitive": "sphere", "radius": 0.42, "segments": 96, "rings": 48 }, "material": "a%s" }%s\n' \
        "${names[$i]}" "$(echo "$i - 2" | bc).0" "${names[$i]}" "$([ $i -lt 4 ] && echo ,)"
    done
    echo '  ],'
    echo '  "lights": []'
    echo '}'; }
}
# pareto_front MEAN.csv [COLUMN]: the rows of MEAN.csv (alpha,method,ms,error,..., sorted by alpha
# then ms) that are more accurate (the error in COLUMN, default 4) than every faster row of the same
# alpha: the error-vs-ms Pareto front.
pareto_front() {
    awk -F, -v c="${2:-4}" '{ a = $1; if (a != last) { best = 1e30; last = a } if ($c < best) { best = $c; print $0 } }' "$1"
}
# gp WxH FONTSIZE COMMANDS: gnuplot to PNG (pngcairo when the build has it, else png)
gp() {
    gnuplot -e "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size $1 font 'sans,$2' } else { set terminal png size $1 }; set termoption noenhanced; $3"
}
# gp_noisy FILE XCOL YCOL: a gnuplot plot element marking FILE's rows as shadelab-bench marks a
# noisy setting (tools/bench/report.c, tools/bench/README.md "Noisy settings": an orange cross; its
# noise in its label, off every Pareto front). Noisy = the benches' `noisy` column, which compares
# the noise with SL_NOISE_VISIBLE (tools/bench/include/bench/metrics.h).
gp_noisy() {
    printf "%s" "'$1' using $2:$3 with points pt 2 ps 1.8 lw 2 lc rgb '#ff7f0e' title 'noisy (its frames scatter visibly: on no front)'"
}
