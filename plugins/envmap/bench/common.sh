# Sourced by envmap's bench scripts after they set $here (this directory): the repository root,
# the build directory (the script's first argument, else build/) and blender_hdr.
root=$(cd "$here/../../.." && pwd)
build=${1:-$root/build}
# blender_hdr NAME: the path of Blender's studio-light environment NAME.exr (Debian blender-data,
# with or without a version directory), empty when it is not installed.
blender_hdr() {
    ls /usr/share/blender/*/datafiles/studiolights/world/"$1".exr \
       /usr/share/blender/datafiles/studiolights/world/"$1".exr 2>/dev/null | head -1 || true
}
