"""reference_scene.py - Blender's half of bench/peer/reference_render.sh: meshes
one particle frame and path-traces it with Cycles as clear water under the sky,
sun and checkered floor of fluidcast's built-in scene.

    blender -b --factory-startup -P reference_scene.py -- \
        --particles XYZ.f32 --out IMAGE.png --size WxH --eye X,Y,Z --target X,Y,Z \
        --up X,Y,Z --fov DEG --radius R [--samples N] [--mesh-scale S] \
        [--voxel-scale V] [--absorption R,G,B] [--threads N] [--blend FILE]

XYZ.f32 is raw float32 x y z (reference_render.sh converts .ply to it).

The scene mirrors fluidcast's, one fact each, so that a change there must be
copied here (the constants below name their source):
  - floor: server/render/environment.c fc_environment_for_view: perpendicular
    to up, at the particles' lowest point minus the radius; checkers of
    (box diagonal + 2 radius) / 10 along the world axis least aligned with up;
    the square [0,1)^2 dark; fog towards the horizon colour over 60 checkers.
  - sun: environment.c place_sun: 35 degrees high, 65 degrees round from
    straight behind the camera towards its right.
  - sky, sun colour, floor colours and light: shaders/environment.frag.glsl
    (sky_radiance, floor_radiance).
  - image: environment.frag.glsl display_color: exposure 1, the ACES filmic fit
    (Narkowicz), then sRGB, as fluidcast's 8-bit output.
Water: a sharp glass surface with IOR 1.33 and weak Beer-Lambert absorption
inside. Shadow rays pass the surface (Cycles renders no caustics from a sun),
so the floor's shadow is the absorption along the sun ray, as fluidcast's.
Meshing: geometry nodes Mesh to Points -> Points to Volume (spheres of
mesh-scale x radius on voxels of voxel-scale x radius) -> Volume to Mesh, then
islands of negative signed volume (the voids between spheres) deleted,
and a Smooth modifier (30 passes) that rounds off the voxel steps and the
particle-scale roughness.
"""
import argparse
import math
import struct
import sys
import time
import zlib

import bpy
import numpy as np
from mathutils import Matrix, Vector

# environment.c
SUN_ELEVATION_DEG = 35.0
SUN_AZIMUTH_FROM_BEHIND_DEG = 65.0
CHECKERS_PER_DIAGONAL = 10.0
# environment.frag.glsl
ZENITH = (0.16, 0.34, 0.78)
HORIZON = (1.05, 1.08, 1.10)
GROUND_NEAR_HORIZON = (0.36, 0.33, 0.29)
GROUND = (0.16, 0.14, 0.12)
SUN_COLOR = (1.00, 0.93, 0.82)
SUN_DISC_COS = 0.99985
SUN_IRRADIANCE = 1.4
CHECKER_LIGHT = (0.62, 0.60, 0.56)
CHECKER_DARK = (0.20, 0.21, 0.23)
FOG_DISTANCE_IN_CHECKERS = 200.0
# fluidcast's default IOR (proto/fc_settings.c)
IOR = 1.33
# Weak absorption: fluidcast's default (proto/fc_settings.c).
DEFAULT_ABSORPTION_PER_RADIUS = (0.02, 0.007, 0.0035)


def vec3(text):
    v = [float(x) for x in text.split(",")]
    if len(v) != 3:
        raise argparse.ArgumentTypeError(f"'{text}' is not X,Y,Z")
    return np.array(v)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="reference_scene.py")
    p.add_argument("--particles", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--size", required=True)
    p.add_argument("--eye", type=vec3, required=True)
    p.add_argument("--target", type=vec3, required=True)
    p.add_argument("--up", type=vec3, required=True)
    p.add_argument("--fov", type=float, required=True)
    p.add_argument("--radius", type=float, required=True)
    p.add_argument("--samples", type=int, default=32)
    p.add_argument("--mesh-scale", type=float, default=2.0)
    p.add_argument("--voxel-scale", type=float, default=0.5)
    p.add_argument("--smooth", type=int, default=30, help="passes of vertex smoothing")
    p.add_argument("--absorption", type=vec3, help="per world unit (default: 0.02,0.007,0.0035 per radius)")
    p.add_argument("--threads", type=int, default=0, help="0: Blender's choice")
    p.add_argument("--blend", help="also save the scene to this .blend file")
    args = p.parse_args(argv)
    w, h = (int(x) for x in args.size.lower().split("x"))
    args.size = (w, h)
    return args


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


# --- fluidcast's scene -----------------------------------------------------

def floor_axes(up):
    """environment.c floor_axes."""
    axis = int(np.argmin(np.abs(up)))
    u = np.eye(3)[axis] - up * up[axis]
    u = unit(u)
    return u, np.cross(up, u)


def sun_direction(eye, target, up):
    """environment.c place_sun."""
    back = eye - target
    back = back - np.dot(back, up) * up
    if np.dot(back, back) < 1e-12:
        back = np.cross(up, [1.0, 0.0, 0.0] if abs(up[0]) < 0.9 else [0.0, 1.0, 0.0])
    back = unit(back)
    right = np.cross(up, back)
    az, el = math.radians(SUN_AZIMUTH_FROM_BEHIND_DEG), math.radians(SUN_ELEVATION_DEG)
    return unit(math.cos(el) * (math.cos(az) * back + math.sin(az) * right) + math.sin(el) * up)


def sky_radiance(dirs, up, sun):
    """environment.frag.glsl sky_radiance without the disc (the sun lamp is it)."""
    e = dirs @ up
    t = np.power(np.clip(e, 0, None), 0.45)[:, None]
    sky = (1 - t) * np.array(HORIZON) + t * np.array(ZENITH)
    g = np.power(np.minimum(np.clip(-e, 0, None) * 4, 1), 0.6)[:, None]
    ground = (1 - g) * np.array(GROUND_NEAR_HORIZON) + g * np.array(GROUND)
    out = np.where((e >= 0)[:, None], sky, ground)
    s = np.clip(dirs @ sun, 0, None)
    return out + np.array(SUN_COLOR) * (0.35 * s ** 12 + 1.5 * s ** 300)[:, None]


def sky_diffuse_scale(up, sun):
    """Per channel, what makes a floor lit by this sky (Cycles: albedo x the
    cosine-weighted mean radiance) get fluidcast's sky light, 0.25 (horizon +
    zenith): the world is scaled by it for diffuse rays only."""
    rng = np.random.default_rng(1)
    d = rng.normal(size=(200000, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    cos = d @ up
    d, cos = d[cos > 0], cos[cos > 0]
    # cosine-weighted mean over the hemisphere: (1/pi) integral L cos dw
    irradiance = 2.0 * (sky_radiance(d, up, sun) * cos[:, None]).mean(axis=0)
    return 0.25 * (np.array(HORIZON) + np.array(ZENITH)) / irradiance


# --- Blender nodes ---------------------------------------------------------

class Nodes:
    """A node tree and terse ways to add math to it."""

    def __init__(self, tree):
        self.tree = tree
        tree.nodes.clear()

    def add(self, kind, **props):
        node = self.tree.nodes.new(kind)
        for name, value in props.items():
            setattr(node, name, value)
        return node

    def link(self, out, into):
        self.tree.links.new(out, into)

    def set_or_link(self, socket, value):
        if isinstance(value, bpy.types.NodeSocket):
            self.link(value, socket)
        else:
            socket.default_value = value

    def math(self, op, a, b=0.0):
        node = self.add("ShaderNodeMath", operation=op)
        self.set_or_link(node.inputs[0], a)
        self.set_or_link(node.inputs[1], b)
        return node.outputs[0]

    def vmath(self, op, a, b=(0.0, 0.0, 0.0), scale=None):
        node = self.add("ShaderNodeVectorMath", operation=op)
        self.set_or_link(node.inputs[0], a)
        self.set_or_link(node.inputs[1], b)
        if scale is not None:
            self.set_or_link(node.inputs["Scale"], scale)
        return node.outputs["Value" if op == "DOT_PRODUCT" else "Vector"]

    def mix(self, fac, a, b):
        node = self.add("ShaderNodeMixRGB", blend_type="MIX", use_clamp=False)
        self.set_or_link(node.inputs["Fac"], fac)
        self.set_or_link(node.inputs["Color1"], a if not isinstance(a, tuple) else (*a, 1.0))
        self.set_or_link(node.inputs["Color2"], b if not isinstance(b, tuple) else (*b, 1.0))
        return node.outputs["Color"]


def make_world(up, sun):
    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    n = Nodes(world.node_tree)
    direction = n.add("ShaderNodeTexCoord").outputs["Generated"]
    direction = n.vmath("NORMALIZE", direction)
    e = n.vmath("DOT_PRODUCT", direction, tuple(up))
    t = n.math("POWER", n.math("MAXIMUM", e, 0.0), 0.45)
    sky = n.mix(t, HORIZON, ZENITH)
    g = n.math("POWER", n.math("MINIMUM", n.math("MULTIPLY", n.math("MAXIMUM", n.math("MULTIPLY", e, -1.0), 0.0),
                                                 4.0), 1.0), 0.6)
    ground = n.mix(g, GROUND_NEAR_HORIZON, GROUND)
    above = n.math("GREATER_THAN", e, -1e-6)
    base = n.mix(above, ground, sky)
    s = n.math("MAXIMUM", n.vmath("DOT_PRODUCT", direction, tuple(sun)), 0.0)
    glow = n.math("ADD", n.math("MULTIPLY", n.math("POWER", s, 12.0), 0.35),
                  n.math("MULTIPLY", n.math("POWER", s, 300.0), 1.5))
    radiance = n.vmath("ADD", base, n.vmath("SCALE", SUN_COLOR, scale=glow))
    # diffuse rays see the sky scaled so the floor's sky light is fluidcast's
    path = n.add("ShaderNodeLightPath").outputs["Is Diffuse Ray"]
    diffuse_scale = n.mix(path, (1.0, 1.0, 1.0), tuple(sky_diffuse_scale(up, sun)))
    radiance = n.vmath("MULTIPLY", radiance, diffuse_scale)
    background = n.add("ShaderNodeBackground")
    n.link(radiance, background.inputs["Color"])
    out = n.add("ShaderNodeOutputWorld")
    n.link(background.outputs["Background"], out.inputs["Surface"])
    return world


def make_floor_material(u, v, checker):
    mat = bpy.data.materials.new("floor")
    mat.use_nodes = True
    n = Nodes(mat.node_tree)
    position = n.add("ShaderNodeNewGeometry").outputs["Position"]
    a = n.math("FLOOR", n.math("DIVIDE", n.vmath("DOT_PRODUCT", position, tuple(u)), checker))
    b = n.math("FLOOR", n.math("DIVIDE", n.vmath("DOT_PRODUCT", position, tuple(v)), checker))
    parity = n.math("ABSOLUTE", n.math("MODULO", n.math("ADD", a, b), 2.0))   # 0 on [0,1)^2: dark
    albedo = n.mix(parity, CHECKER_DARK, CHECKER_LIGHT)
    diffuse = n.add("ShaderNodeBsdfDiffuse")
    n.link(albedo, diffuse.inputs["Color"])
    fog_emission = n.add("ShaderNodeEmission")
    fog_emission.inputs["Color"].default_value = (*HORIZON, 1.0)
    length = n.add("ShaderNodeLightPath").outputs["Ray Length"]
    fog = n.math("SUBTRACT", 1.0, n.math("EXPONENT", n.math("DIVIDE", length,
                                                            -FOG_DISTANCE_IN_CHECKERS * checker)))
    mix = n.add("ShaderNodeMixShader")
    n.link(fog, mix.inputs["Fac"])
    n.link(diffuse.outputs["BSDF"], mix.inputs[1])
    n.link(fog_emission.outputs["Emission"], mix.inputs[2])
    out = n.add("ShaderNodeOutputMaterial")
    n.link(mix.outputs["Shader"], out.inputs["Surface"])
    return mat


def make_water_material(absorption):
    mat = bpy.data.materials.new("water")
    mat.use_nodes = True
    n = Nodes(mat.node_tree)
    glass = n.add("ShaderNodeBsdfGlass", distribution="SHARP")
    glass.inputs["IOR"].default_value = IOR
    glass.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    transparent = n.add("ShaderNodeBsdfTransparent")
    shadow = n.add("ShaderNodeLightPath").outputs["Is Shadow Ray"]
    surface = n.add("ShaderNodeMixShader")
    n.link(shadow, surface.inputs["Fac"])
    n.link(glass.outputs["BSDF"], surface.inputs[1])
    n.link(transparent.outputs["BSDF"], surface.inputs[2])
    # Volume Absorption's coefficient is density x (1 - colour): density the
    # largest coefficient, the colour's channels the rest.
    density = float(max(absorption))
    volume = n.add("ShaderNodeVolumeAbsorption")
    volume.inputs["Density"].default_value = density
    volume.inputs["Color"].default_value = (*(1.0 - np.asarray(absorption) / density), 1.0)
    out = n.add("ShaderNodeOutputMaterial")
    n.link(surface.outputs["Shader"], out.inputs["Surface"])
    n.link(volume.outputs["Volume"], out.inputs["Volume"])
    return mat


def socket(sockets, identifier):
    """A socket by identifier: names repeat across a node's data types."""
    return next(s for s in sockets if s.identifier == identifier)


def make_fluid(xyz, radius, args, material):
    mesh = bpy.data.meshes.new("particles")
    mesh.vertices.add(len(xyz))
    mesh.vertices.foreach_set("co", xyz.astype(np.float32).ravel())
    mesh.update()
    obj = bpy.data.objects.new("fluid", mesh)
    bpy.context.scene.collection.objects.link(obj)
    tree = bpy.data.node_groups.new("mesh_particles", "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    nodes, links = tree.nodes, tree.links
    group_in, group_out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    to_points = nodes.new("GeometryNodeMeshToPoints")
    to_points.mode = "VERTICES"
    to_volume = nodes.new("GeometryNodePointsToVolume")
    to_volume.resolution_mode = "VOXEL_SIZE"
    to_volume.inputs["Density"].default_value = 1.0
    to_volume.inputs["Voxel Size"].default_value = args.voxel_scale * radius
    to_volume.inputs["Radius"].default_value = args.mesh_scale * radius
    to_mesh = nodes.new("GeometryNodeVolumeToMesh")
    to_mesh.resolution_mode = "GRID"
    to_mesh.inputs["Threshold"].default_value = 0.5
    # Volume to Mesh also closes the small voids the spheres leave inside the
    # fluid: surfaces of their own, facing inwards, which a glass shader
    # draws as grain. Each island's signed volume (the sum of position .
    # normal x area / 3 over its faces) is negative for a void: those go.
    island = nodes.new("GeometryNodeInputMeshIsland")
    area = nodes.new("GeometryNodeInputMeshFaceArea")
    position = nodes.new("GeometryNodeInputPosition")
    normal = nodes.new("GeometryNodeInputNormal")
    dot = nodes.new("ShaderNodeVectorMath")
    dot.operation = "DOT_PRODUCT"
    volume = nodes.new("ShaderNodeMath")
    volume.operation = "MULTIPLY"
    accumulate = nodes.new("GeometryNodeAccumulateField")
    accumulate.data_type = "FLOAT"
    accumulate.domain = "FACE"
    is_void = nodes.new("FunctionNodeCompare")
    is_void.data_type = "FLOAT"
    is_void.operation = "LESS_THAN"
    is_void.inputs["B"].default_value = 0.0
    delete = nodes.new("GeometryNodeDeleteGeometry")
    delete.domain = "FACE"
    links.new(position.outputs["Position"], dot.inputs[0])
    links.new(normal.outputs["Normal"], dot.inputs[1])
    links.new(dot.outputs["Value"], volume.inputs[0])
    links.new(area.outputs["Area"], volume.inputs[1])
    links.new(volume.outputs["Value"], socket(accumulate.inputs, "Value Float"))
    links.new(island.outputs["Island Index"], accumulate.inputs["Group Index"])
    links.new(socket(accumulate.outputs, "Total Float"), is_void.inputs["A"])
    links.new(is_void.outputs["Result"], delete.inputs["Selection"])
    smooth = nodes.new("GeometryNodeSetShadeSmooth")
    set_material = nodes.new("GeometryNodeSetMaterial")
    set_material.inputs["Material"].default_value = material
    links.new(group_in.outputs[0], to_points.inputs["Mesh"])
    links.new(to_points.outputs["Points"], to_volume.inputs["Points"])
    links.new(to_volume.outputs["Volume"], to_mesh.inputs["Volume"])
    links.new(to_mesh.outputs["Mesh"], delete.inputs["Geometry"])
    links.new(delete.outputs["Geometry"], smooth.inputs["Geometry"])
    links.new(smooth.outputs["Geometry"], set_material.inputs["Geometry"])
    links.new(set_material.outputs["Geometry"], group_out.inputs[0])
    modifier = obj.modifiers.new("mesh_particles", "NODES")
    modifier.node_group = tree
    # the voxel steps rounded off: a few passes of vertex smoothing
    relax = obj.modifiers.new("relax", "SMOOTH")
    relax.factor = 0.5
    relax.iterations = args.smooth
    return obj


def make_floor(up, u, v, height, centre, checker, material):
    half = 400.0 * checker   # far past where the fog has made it the horizon's colour
    base = centre - np.dot(centre, up) * up + height * up
    corners = [base + su * half * u + sv * half * v for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    mesh = bpy.data.meshes.new("floor")
    mesh.from_pydata([tuple(c) for c in corners], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    obj = bpy.data.objects.new("floor", mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def make_sun(sun):
    light = bpy.data.lights.new("sun", "SUN")
    # Cycles: a sun of strength E lights a diffuse surface to albedo E cos / pi;
    # fluidcast's floor gets albedo SUN_IRRADIANCE cos.
    light.energy = SUN_IRRADIANCE * math.pi
    light.color = SUN_COLOR
    light.angle = 2.0 * math.acos(SUN_DISC_COS)
    obj = bpy.data.objects.new("sun", light)
    obj.rotation_euler = Vector(tuple(sun)).to_track_quat("Z", "Y").to_euler()
    bpy.context.scene.collection.objects.link(obj)
    return obj


def make_camera(eye, target, up, fov, size):
    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(fov)
    data.clip_start = 0.01
    data.clip_end = 1000.0
    obj = bpy.data.objects.new("camera", data)
    forward = unit(target - eye)
    right = unit(np.cross(forward, up))
    true_up = np.cross(right, forward)
    rot = Matrix([tuple(right), tuple(true_up), tuple(-forward)]).transposed()   # columns: x, y, z
    obj.matrix_world = Matrix.Translation(Vector(tuple(eye))) @ rot.to_4x4()
    bpy.context.scene.collection.objects.link(obj)
    scene = bpy.context.scene
    scene.camera = obj
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    return obj


def setup_cycles(args):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = args.samples
    cycles.use_adaptive_sampling = False
    cycles.max_bounces = 24
    cycles.transmission_bounces = 24
    cycles.glossy_bounces = 8
    cycles.transparent_max_bounces = 24
    cycles.diffuse_bounces = 2
    cycles.volume_bounces = 0
    cycles.caustics_reflective = False
    cycles.caustics_refractive = False
    cycles.seed = 0
    cycles.use_denoising = False   # Debian's Blender 3.4 has no OpenImageDenoise: samples it is
    if args.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = args.threads
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.exposure = 0.0


# --- output: fluidcast's tone map, then sRGB, as PNG --------------------------

def filmic(x):
    """environment.frag.glsl filmic (Narkowicz's ACES fit)."""
    return np.clip(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)


def srgb(x):
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(np.clip(x, 0.0031308, None), 1 / 2.4) - 0.055)


def write_png(path, rgb8):
    h, w, _ = rgb8.shape
    raw = b"".join(b"\x00" + rgb8[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def render_to_png(path, size):
    scene = bpy.context.scene
    exr = path + ".exr"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = exr
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(exr)
    image.colorspace_settings.name = "Linear"
    w, h = size
    pixels = np.empty(w * h * 4, np.float32)
    image.pixels.foreach_get(pixels)
    linear = pixels.reshape(h, w, 4)[::-1, :, :3]   # Blender's rows run bottom up
    rgb8 = np.round(srgb(filmic(np.clip(linear, 0, None))) * 255).astype(np.uint8)
    write_png(path, np.ascontiguousarray(rgb8))
    return exr


def main():
    args = parse_args()
    xyz = np.fromfile(args.particles, dtype="<f4").reshape(-1, 3).astype(np.float64)
    up = unit(args.up)
    lo, hi = xyz.min(axis=0), xyz.max(axis=0)
    corners = np.array([[hi[i] if (c >> i) & 1 else lo[i] for i in range(3)] for c in range(8)])
    floor_height = float((corners @ up).min()) - args.radius
    checker = (float(np.linalg.norm(hi - lo)) + 2 * args.radius) / CHECKERS_PER_DIAGONAL
    u, v = floor_axes(up)
    sun = sun_direction(args.eye, args.target, up)
    absorption = args.absorption if args.absorption is not None else \
        np.array(DEFAULT_ABSORPTION_PER_RADIUS) / args.radius

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    setup_cycles(args)
    scene.world = make_world(up, sun)
    make_floor(up, u, v, floor_height, (lo + hi) / 2, checker, make_floor_material(u, v, checker))
    make_fluid(xyz, args.radius, args, make_water_material(absorption))
    make_sun(sun)
    make_camera(args.eye, args.target, up, args.fov, args.size)
    print(f"reference_scene: {len(xyz)} particles, floor at {floor_height:.6g}, checker {checker:.6g}, "
          f"sun {np.round(sun, 4).tolist()}, absorption {np.round(absorption, 4).tolist()} per unit")
    if args.blend:
        bpy.ops.wm.save_as_mainfile(filepath=args.blend)
    started = time.monotonic()
    render_to_png(args.out, args.size)
    print(f"reference_scene: meshed and rendered in {time.monotonic() - started:.1f} s")


main()
