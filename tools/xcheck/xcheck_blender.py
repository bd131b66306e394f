# Builds a shadelab scene exported by shadelab-xcheck in Blender and renders it with Cycles.
#
#   blender -b --factory-startup --python scene.py -- OUTDIR
#
# scene.py (written by shadelab-xcheck) sets XCHECK_DIR and runs this file; the scene itself is
# scene.json beside it, meshes and images under assets/. Every unit conversion is decided in
# shadelab-xcheck (tools/xcheck/export.c) and documented in docs/xcheck.md; this file only
# builds what scene.json says. Coordinates stay shadelab's (Y up): every object hangs under one
# root empty turned +90 degrees about X, which is Blender's Z-up frame.
import array
import json
import math
import os
import sys
import time

import bpy
from mathutils import Matrix


def fail(msg):
    print("xcheck-blender: error: " + msg, file=sys.stderr)
    sys.stderr.flush()
    os._exit(1)


def clear_file():
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.lights,
                       bpy.data.cameras, bpy.data.images, bpy.data.worlds):
        for item in list(collection):
            collection.remove(item)


def matrix(values):
    """A 4x4 from 16 column-major floats (shadelab's layout)."""
    return Matrix([[values[c * 4 + r] for c in range(4)] for r in range(4)])


def link(obj, root):
    bpy.context.scene.collection.objects.link(obj)
    if root is not None:
        obj.parent = root


# ---------------------------------------------------------------------------------- meshes --

def load_mesh(d, name, spec):
    """Positions, normals, UVs (float32) and triangle indices (uint32), little-endian, in one file.
    Read with the array module: Blender's Python need not have numpy."""
    n, t = spec["vertex_count"], spec["triangle_count"]
    with open(os.path.join(d, spec["file"]), "rb") as f:
        raw = f.read()
    if len(raw) != (n * 8 + t * 3) * 4:
        fail("%s: %d bytes, expected %d" % (spec["file"], len(raw), (n * 8 + t * 3) * 4))
    floats = array.array("f", raw[:n * 32])
    idx = array.array("I", raw[n * 32:])
    if sys.byteorder != "little":
        floats.byteswap()
        idx.byteswap()
    me = bpy.data.meshes.new(name)
    me.vertices.add(n)
    me.vertices.foreach_set("co", floats[0:n * 3])
    me.loops.add(t * 3)
    me.loops.foreach_set("vertex_index", idx)
    me.polygons.add(t)
    me.polygons.foreach_set("loop_start", array.array("i", range(0, t * 3, 3)))
    me.polygons.foreach_set("loop_total", array.array("i", [3]) * t)
    me.polygons.foreach_set("use_smooth", [True] * t)
    layer = me.uv_layers.new(name="UVMap")
    uv = floats[n * 6:n * 8]
    loop_uv = array.array("f", bytes(8 * t * 3))
    for k, v in enumerate(idx):
        loop_uv[2 * k] = uv[2 * v]
        loop_uv[2 * k + 1] = uv[2 * v + 1]
    layer.data.foreach_set("uv", loop_uv)
    me.update()
    me.use_auto_smooth = True
    nrm = floats[n * 3:n * 6]
    me.normals_split_custom_set_from_vertices([nrm[3 * v:3 * v + 3] for v in range(n)])
    return me


# ------------------------------------------------------------------------------- materials --

class Nodes:
    def __init__(self, tree, d):
        self.tree, self.d = tree, d
        self.images = {}

    def new(self, kind, **props):
        node = self.tree.nodes.new(kind)
        for k, v in props.items():
            setattr(node, k, v)
        return node

    def link(self, out, inp):
        self.tree.links.new(out, inp)

    def image(self, tex):
        """An Image Texture node for {"file", "colorspace", "extension"}; its Color output."""
        key = (tex["file"], tex["colorspace"], tex.get("extension", "REPEAT"))
        if key not in self.images:
            img = bpy.data.images.load(os.path.join(self.d, tex["file"]), check_existing=True)
            img.colorspace_settings.name = tex["colorspace"]
            node = self.new("ShaderNodeTexImage", image=img, interpolation="Linear",
                            extension=tex.get("extension", "REPEAT"))
            self.images[key] = node
        return self.images[key]

    def value(self, spec, socket, channel=None):
        """Feeds socket from spec: a number or colour, or {"texture": {...}, "factor": ...,
        "channel": "R"|"G"|"B"} (texture x factor)."""
        if not isinstance(spec, dict):
            if isinstance(spec, list):
                socket.default_value = list(spec) + [1.0] * (len(socket.default_value) - len(spec))
            else:
                socket.default_value = spec
            return
        out = self.image(spec["texture"]).outputs["Color"]
        ch = spec.get("channel")
        if ch:
            sep = self.new("ShaderNodeSeparateColor")
            self.link(out, sep.inputs[0])
            out = sep.outputs["RGB".index(ch)]
        factor = spec.get("factor")
        if factor is not None:
            if isinstance(factor, list):
                mix = self.new("ShaderNodeMix", data_type="RGBA", blend_type="MULTIPLY")
                mix.inputs["Factor"].default_value = 1.0
                self.link(out, mix.inputs[6])
                mix.inputs[7].default_value = list(factor) + [1.0]
                out = mix.outputs[2]
            else:
                mul = self.new("ShaderNodeMath", operation="MULTIPLY")
                self.link(out, mul.inputs[0])
                mul.inputs[1].default_value = factor
                out = mul.outputs[0]
        self.link(out, socket)

    def normal(self, spec):
        """A Normal Map node (tangent space, UVMap) for {"texture", "strength"}; its output."""
        nm = self.new("ShaderNodeNormalMap", space="TANGENT", uv_map="UVMap")
        nm.inputs["Strength"].default_value = spec.get("strength", 1.0)
        self.link(self.image(spec["texture"]).outputs["Color"], nm.inputs["Color"])
        return nm.outputs["Normal"]


def scaled(nodes, shader_out, weight):
    """shader x weight (a number or a texture spec): mixed with a black diffuse, which adds nothing."""
    if not isinstance(weight, dict) and weight == 1.0:
        return shader_out
    black = nodes.new("ShaderNodeBsdfDiffuse")
    black.inputs["Color"].default_value = (0, 0, 0, 1)
    mix = nodes.new("ShaderNodeMixShader")
    nodes.value(weight, mix.inputs["Fac"])
    nodes.link(black.outputs[0], mix.inputs[1])
    nodes.link(shader_out, mix.inputs[2])
    return mix.outputs[0]


def add(nodes, a, b):
    if a is None:
        return b
    if b is None:
        return a
    s = nodes.new("ShaderNodeAddShader")
    nodes.link(a, s.inputs[0])
    nodes.link(b, s.inputs[1])
    return s.outputs[0]


def principled(nodes, m, base, normal):
    p = nodes.new("ShaderNodeBsdfPrincipled", distribution="GGX", subsurface_method="BURLEY")
    nodes.value(base, p.inputs["Base Color"])
    nodes.value(m.get("metallic", 0.0), p.inputs["Metallic"])
    nodes.value(m["roughness"], p.inputs["Roughness"])
    p.inputs["Specular"].default_value = m.get("specular_level", 0.5)
    p.inputs["Specular Tint"].default_value = 0.0
    p.inputs["Sheen Tint"].default_value = 0.0
    if normal is not None:
        nodes.link(normal, p.inputs["Normal"])
    return p.outputs[0]


def make_material(d, m):
    mat = bpy.data.materials.new(m["name"])
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    nodes = Nodes(tree, d)
    out = nodes.new("ShaderNodeOutputMaterial", target="ALL")
    normal = nodes.normal(m["normal_map"]) if "normal_map" in m else None
    kind = m["kind"]
    shader = None
    if kind in ("diffuse", "diffuse+specular"):
        diff = nodes.new("ShaderNodeBsdfDiffuse")
        nodes.value(m["base_color"], diff.inputs["Color"])
        diff.inputs["Roughness"].default_value = 0.0  # Lambert (Oren-Nayar with sigma 0)
        if normal is not None:
            nodes.link(normal, diff.inputs["Normal"])
        shader = diff.outputs[0]
    if kind == "diffuse+specular":
        # the specular lobe alone: a Principled BSDF with a black base colour has no diffuse
        spec = principled(nodes, dict(m, metallic=0.0), [0.0, 0.0, 0.0], normal)
        shader = add(nodes, shader, scaled(nodes, spec, m.get("specular_weight", 1.0)))
    elif kind == "principled":
        shader = principled(nodes, m, m["base_color"], normal)
    elif kind == "mirror":
        g = nodes.new("ShaderNodeBsdfGlossy", distribution="SHARP")
        nodes.value(m["base_color"], g.inputs["Color"])
        if normal is not None:
            nodes.link(normal, g.inputs["Normal"])
        shader = g.outputs[0]
    if "emission" in m:
        e = nodes.new("ShaderNodeEmission")
        nodes.value(m["emission"], e.inputs["Color"])
        e.inputs["Strength"].default_value = 1.0
        shader = add(nodes, shader, e.outputs[0])
    if shader is None:
        black = nodes.new("ShaderNodeBsdfDiffuse")
        black.inputs["Color"].default_value = (0, 0, 0, 1)
        shader = black.outputs[0]
    nodes.link(shader, out.inputs["Surface"])
    return mat


# ---------------------------------------------------------------------------------- lights --

def spot_falloff(light, spec):
    """Emission strength x the spot's fall-off of the angle from the light's local -Z axis
    (Texture Coordinate > Normal is the outgoing direction in the light's object space)."""
    light.use_nodes = True
    tree = light.node_tree
    em = tree.nodes["Emission"]
    tc = tree.nodes.new("ShaderNodeTexCoord")
    dot = tree.nodes.new("ShaderNodeVectorMath")
    dot.operation = "DOT_PRODUCT"
    dot.inputs[1].default_value = (0.0, 0.0, -1.0)
    tree.links.new(tc.outputs["Normal"], dot.inputs[0])
    cos_theta = dot.outputs["Value"]

    def op(name, a, b=None, clamp=False):
        n = tree.nodes.new("ShaderNodeMath")
        n.operation = name
        n.use_clamp = clamp
        for i, x in enumerate((a, b)):
            if x is None:
                continue
            if isinstance(x, (int, float)):
                n.inputs[i].default_value = x
            else:
                tree.links.new(x, n.inputs[i])
        return n.outputs[0]

    if spec["falloff"] == "gltf":
        # clamp(cos(theta) * scale + offset, 0, 1)^2 (KHR_lights_punctual)
        t = op("MULTIPLY_ADD", cos_theta, spec["scale"], clamp=True)
        t.node.inputs[2].default_value = spec["offset"]
        f = op("MULTIPLY", t, t)
    else:
        # linear in the angle: clamp((1.1 cone - theta) / (0.2 cone), 0, 1)
        theta = op("ARCCOSINE", op("MINIMUM", op("MAXIMUM", cos_theta, -1.0), 1.0))
        f = op("MULTIPLY_ADD", theta, -1.0 / (0.2 * spec["cone"]), clamp=True)
        f.node.inputs[2].default_value = 1.1 / 0.2
    tree.links.new(f, em.inputs["Strength"])


def make_light(l, root, eevee, unoccluded):
    kind = l["blender_type"]
    if eevee and "spot" in l:
        kind = "SPOT"  # EEVEE has no light node trees: Blender's own spot, its edge approximated
    data = bpy.data.lights.new(l["name"], kind)
    data.color = l["color"]
    data.energy = l["energy"]
    shadow = l["shadow"] and not unoccluded
    data.cycles.cast_shadow = shadow
    data.use_shadow = shadow
    data.cycles.max_bounces = 1024
    if kind == "SUN":
        data.angle = l.get("angle", 0.0)
    elif kind == "POINT":
        data.shadow_soft_size = l.get("radius", 0.0)
        if "spot" in l:
            spot_falloff(data, l["spot"])
    elif kind == "SPOT":
        spot = l["spot"]
        outer = spot["cone"] * (1.1 if spot["falloff"] == "linear" else 1.0)
        inner = spot["cone"] * 0.9 if spot["falloff"] == "linear" else math.acos(min(1.0, (1.0 - spot["offset"]) / spot["scale"]))
        data.spot_size = min(2 * outer, math.pi)
        data.spot_blend = max(0.0, min(1.0, 1.0 - inner / outer))
        data.shadow_soft_size = l.get("radius", 0.0)
        data.use_shadow = shadow
    elif kind == "AREA":
        data.shape = l["shape"]
        data.size, data.size_y = l["size"]
    obj = bpy.data.objects.new(l["name"], data)
    obj.matrix_basis = matrix(l["matrix"])
    link(obj, root)


# ----------------------------------------------------------------------------------- world --

def add_sun_disk(tree, direction, colour, sun):
    """The procedural sky's sun disk as camera rays see it, drawn exactly: colour + radiance where
    the lookup direction is within the disk's angular radius (dot > cos r) and the ray is a camera
    ray; every other ray finds the sun as its lamp (one of scene.json's lights, export.c's
    export_sun). Returns the sum's output socket."""
    def vmath(op):
        n = tree.nodes.new("ShaderNodeVectorMath")
        n.operation = op
        return n
    unit = vmath("NORMALIZE")
    tree.links.new(direction, unit.inputs[0])
    dot = vmath("DOT_PRODUCT")
    tree.links.new(unit.outputs["Vector"], dot.inputs[0])
    dot.inputs[1].default_value = sun["direction"]
    inside = tree.nodes.new("ShaderNodeMath")
    inside.operation = "GREATER_THAN"
    tree.links.new(dot.outputs["Value"], inside.inputs[0])
    inside.inputs[1].default_value = sun["cos_radius"]
    seen = tree.nodes.new("ShaderNodeMath")
    seen.operation = "MULTIPLY"
    tree.links.new(inside.outputs["Value"], seen.inputs[0])
    tree.links.new(tree.nodes.new("ShaderNodeLightPath").outputs["Is Camera Ray"], seen.inputs[1])
    disk = vmath("SCALE")
    disk.inputs[0].default_value = sun["radiance"]
    tree.links.new(seen.outputs["Value"], disk.inputs["Scale"])
    total = vmath("ADD")
    tree.links.new(colour, total.inputs[0])
    tree.links.new(disk.outputs["Vector"], total.inputs[1])
    return total.outputs["Vector"]


def make_world(d, w):
    world = bpy.data.worlds.new("shadelab")
    world.use_nodes = True
    tree = world.node_tree
    bg = tree.nodes["Background"]
    bg.inputs["Strength"].default_value = w.get("strength", 1.0)
    if "map" in w:
        tex = tree.nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(os.path.join(d, w["map"]["file"]))
        tex.image.colorspace_settings.name = w["map"]["colorspace"]
        tex.interpolation = "Linear"
        tex.projection = "EQUIRECTANGULAR"
        coord = tree.nodes.new("ShaderNodeTexCoord")
        rot = tree.nodes.new("ShaderNodeMapping")
        rot.vector_type = "VECTOR"
        rot.inputs["Rotation"].default_value = (0.0, 0.0, w["map"]["rotate_z"])
        tree.links.new(coord.outputs["Generated"], rot.inputs["Vector"])
        tree.links.new(rot.outputs["Vector"], tex.inputs["Vector"])
        colour = tex.outputs["Color"]
        if "sun" in w:
            colour = add_sun_disk(tree, rot.outputs["Vector"], colour, w["sun"])
        tree.links.new(colour, bg.inputs["Color"])
    else:
        bg.inputs["Color"].default_value = list(w.get("color", [0, 0, 0])) + [1.0]
    world.cycles.sampling_method = "AUTOMATIC" if "map" in w else "NONE"
    return world


# ---------------------------------------------------------------------------------- camera --

def make_camera(c, root):
    cam = bpy.data.cameras.new("camera")
    cam.sensor_fit = "VERTICAL"
    if c["type"] == "orthographic":
        cam.type = "ORTHO"
        cam.ortho_scale = 2.0 * c["ymag"]
    else:
        cam.angle_y = math.radians(c["fov_y"])
    cam.clip_start, cam.clip_end = c["near"], c["far"]
    obj = bpy.data.objects.new("camera", cam)
    obj.matrix_basis = matrix(c["matrix"])
    link(obj, root)
    bpy.context.scene.camera = obj


# ---------------------------------------------------------------------------------- render --

def setup_render(S, out_dir):
    sc = bpy.context.scene
    r = S["render"]
    sc.render.engine = "CYCLES"
    sc.cycles.device = "CPU"
    sc.cycles.samples = r["samples"]
    sc.cycles.use_adaptive_sampling = False
    sc.cycles.use_denoising = False
    sc.cycles.seed = r.get("seed", 0)
    sc.cycles.max_bounces = r["bounces"]
    for k in ("diffuse_bounces", "glossy_bounces", "transmission_bounces", "volume_bounces"):
        setattr(sc.cycles, k, r["bounces"])
    sc.cycles.transparent_max_bounces = 8
    sc.cycles.sample_clamp_direct = 0.0
    sc.cycles.sample_clamp_indirect = 0.0
    sc.cycles.blur_glossy = 0.0
    sc.cycles.caustics_reflective = True
    sc.cycles.caustics_refractive = True
    sc.cycles.pixel_filter_type = "BOX"
    sc.cycles.filter_width = 1.0
    sc.render.resolution_x, sc.render.resolution_y = r["width"], r["height"]
    sc.render.resolution_percentage = 100
    sc.render.film_transparent = False
    sc.view_settings.view_transform = "Standard"
    sc.view_settings.look = "None"
    sc.view_settings.exposure = r.get("exposure", 0.0)
    sc.view_settings.gamma = 1.0
    # scene time 0, the time shadelab renders: Blender's glTF importer puts a key at time t on frame
    # t * fps (io_scene_gltf2/blender/imp/gltf2_blender_animation_node.py), so time 0 is frame 0;
    # frame 1 (the scene's start) would show an animated model 1/fps seconds later
    sc.frame_current = 0
    layer = sc.view_layers[0]
    layer.use_pass_object_index = True
    # compositor: the linear combined image and the object index as 32-bit EXRs
    sc.use_nodes = True
    tree = sc.node_tree
    tree.nodes.clear()
    rl = tree.nodes.new("CompositorNodeRLayers")
    fo = tree.nodes.new("CompositorNodeOutputFile")
    fo.base_path = out_dir
    fo.format.file_format = "OPEN_EXR"
    fo.format.color_depth = "32"
    fo.format.color_mode = "RGBA"
    fo.format.exr_codec = "ZIP"
    fo.file_slots.clear()
    fo.file_slots.new("combined_")
    fo.file_slots.new("index_")
    tree.links.new(rl.outputs["Image"], fo.inputs[0])
    tree.links.new(rl.outputs["IndexOB"], fo.inputs[1])
    comp = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(rl.outputs["Image"], comp.inputs[0])


def default_material_where_none(o):
    """glTF 2.0 §3.9.6: a primitive without a material is drawn with the default material (base
    colour 1, metallicFactor 1, roughnessFactor 1); Blender's importer leaves it without one, which
    Cycles draws as its own grey diffuse. The spec's material goes where the importer left none."""
    if o.data.materials and all(m is not None for m in o.data.materials):
        return
    mat = bpy.data.materials.get("glTF default material")
    if mat is None:
        mat = bpy.data.materials.new("glTF default material")
        mat.use_nodes = True
        p = mat.node_tree.nodes["Principled BSDF"]
        p.distribution = "GGX"
        p.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        p.inputs["Metallic"].default_value = 1.0
        p.inputs["Roughness"].default_value = 1.0
    if not o.data.materials:
        o.data.materials.append(mat)
    for k, m in enumerate(o.data.materials):
        if m is None:
            o.data.materials[k] = mat


def import_gltf(d, g, out_dir):
    """Blender's own glTF importer reads the file (geometry, materials); its lights and cameras are
    dropped (the export's stand for them). The mesh objects get pass indices 1..N by name, listed in
    OUT/objects.json for the report."""
    import numpy
    if not hasattr(numpy, "bool"):
        numpy.bool = bool  # Blender 3.4's importer uses the alias that numpy 1.24 removed
    path = g["file"] if os.path.isabs(g["file"]) else os.path.join(d, g["file"])
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=path)
    new = [o for o in bpy.data.objects if o not in before]
    for o in [o for o in new if o.type in ("LIGHT", "CAMERA")]:
        bpy.data.objects.remove(o)
    meshes = sorted([o for o in bpy.data.objects if o.type == "MESH" and o.pass_index == 0 and o not in before],
                    key=lambda o: o.name)
    listed = []
    for i, o in enumerate(meshes):
        o.pass_index = i + 1
        default_material_where_none(o)
        names = [m.name for m in o.data.materials if m is not None]
        listed.append({"index": i + 1, "name": o.name, "material": ", ".join(names)})
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "objects.json"), "w") as f:
        json.dump({"objects": listed}, f, indent=1)


def camera_rays_only():
    """render.object_rays == "camera" (shadelab-xcheck --unoccluded): every mesh object is seen by
    camera rays only, so no object occludes, shadows or reflects any object, itself included; each
    surface sees the environment and the lights alone."""
    for o in bpy.data.objects:
        if o.type == "MESH":
            o.visible_camera = True
            o.visible_diffuse = o.visible_glossy = o.visible_transmission = False
            o.visible_volume_scatter = o.visible_shadow = False


def setup_eevee(S, samples, out_dir):
    """EEVEE as a peer: the same scene, soft shadows, ambient occlusion and screen-space
    reflections on (off for an unoccluded reference: what they add is occlusion and
    inter-reflection), `samples` anti-aliasing samples, the linear image to OUT/eevee_0000.exr."""
    sc = bpy.context.scene
    sc.render.engine = "BLENDER_EEVEE"
    ee = sc.eevee
    ee.taa_render_samples = samples
    unoccluded = S["render"].get("object_rays", "all") == "camera"
    ee.use_soft_shadows = True
    ee.use_gtao = not unoccluded
    ee.use_ssr = not unoccluded
    ee.shadow_cube_size = "1024"
    ee.shadow_cascade_size = "2048"
    sc.render.filter_size = 1.0
    tree = sc.node_tree
    fo = [n for n in tree.nodes if n.bl_idname == "CompositorNodeOutputFile"][0]
    fo.base_path = out_dir
    if len(fo.inputs) > 1:  # EEVEE has no object-index pass: the Cycles one serves
        for link_ in list(fo.inputs[1].links):
            tree.links.remove(link_)
        fo.file_slots.remove(fo.inputs[1])
    fo.file_slots[0].path = "eevee_"


def main():
    d = os.environ.get("XCHECK_DIR") or os.path.dirname(os.path.abspath(__file__))
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out_dir = os.path.abspath(argv[0]) if argv else os.path.join(d, "render")
    with open(os.path.join(d, "scene.json")) as f:
        S = json.load(f)
    clear_file()
    root = bpy.data.objects.new("shadelab_root", None)
    root.rotation_euler = (math.pi / 2, 0.0, 0.0)  # shadelab's Y-up frame in Blender's Z-up one
    link(root, None)
    mats = {m["name"]: make_material(d, m) for m in S["materials"]}
    meshes = {m["name"]: load_mesh(d, m["name"], m) for m in S["meshes"]}
    for o in S["objects"]:
        obj = bpy.data.objects.new(o["name"], meshes[o["mesh"]])
        obj.data.materials.clear()
        obj.active_material = mats[o["material"]]
        obj.matrix_basis = matrix(o["matrix"])
        obj.pass_index = o["index"]
        link(obj, root)
    if "gltf" in S:
        import_gltf(d, S["gltf"], out_dir)
    rays = S["render"].get("object_rays", "all")
    if rays not in ("all", "camera"):
        fail("render.object_rays: %r, expected \"all\" or \"camera\"" % rays)
    if rays == "camera":
        camera_rays_only()
    eevee = int(argv[argv.index("--eevee") + 1]) if "--eevee" in argv else 0
    for l in S["lights"]:
        make_light(l, root, eevee > 0, rays == "camera")
    bpy.context.scene.world = make_world(d, S["world"])
    make_camera(S["camera"], root)
    setup_render(S, out_dir)
    if argv[1:2] == ["--no-render"]:
        return
    if eevee:
        # the first render compiles EEVEE's shaders: one sample, untimed; then the timed one
        setup_eevee(S, 1, out_dir)
        bpy.ops.render.render(write_still=False)
        setup_eevee(S, eevee, out_dir)
        t0 = time.time()
        bpy.ops.render.render(write_still=False)
        print("xcheck-blender: eevee %d samples %.3f ms" % (eevee, 1000 * (time.time() - t0)))
        sys.stdout.flush()
        return
    t0 = time.time()
    bpy.ops.render.render(write_still=False)
    print("xcheck-blender: rendered %dx%d at %d samples in %.2f s" %
          (S["render"]["width"], S["render"]["height"], S["render"]["samples"], time.time() - t0))
    sys.stdout.flush()


try:
    main()
except Exception as e:  # a failed build is an error with its cause, never a half scene rendered
    import traceback
    traceback.print_exc()
    fail(str(e))
