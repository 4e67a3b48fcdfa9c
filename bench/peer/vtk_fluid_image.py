#!/usr/bin/python3
"""vtk_fluid_image.py - the VTK half of bench/peer/compare_images.sh: renders
particle frames with VTK's vtkOpenGLFluidMapper over a checkered floor and a
sky gradient, and puts each next to fluidcast's image of the same frame.

    vtk_fluid_image.py scene --out DIR --size WxH [camera options] FILE...
        Reads the particles, picks the camera, the floor and (for the splash
        data set) the radius, and renders the scene WITHOUT the fluid to
        DIR/floor.png, the background fluidcast is given (--background).
        Writes DIR/scene.json (everything the render step needs) and
        DIR/scene.env (the same for the shell: EYE TARGET UP FOV RADIUS, and
        FRAMES, a file with one "TAG<TAB>PATH" line per input).
    vtk_fluid_image.py render --out DIR [--radius R]
        Renders each frame of DIR/scene.json with the fluid to
        DIR/vtk_TAG.png and composes it with DIR/fc_TAG.png (fluidcast's
        image, made by the caller) into DIR/compare_TAG.png: VTK left,
        fluidcast right, a caption strip above. Prints the paths it wrote.

Both steps render, so both need an X display: run them as
    xvfb-run -a env LIBGL_ALWAYS_SOFTWARE=1 /usr/bin/python3 vtk_fluid_image.py ...
Needs Debian's python3-vtk9 (VTK 9.1) and python3-numpy. Reads .ply (binary
little-endian) and .f32 (float32 xyz) particle files.
"""
import argparse
import json
import math
import os
import re
import shlex
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_scene  # noqa: E402

PROG = "vtk_fluid_image"
DEFAULT_FOV = 40.0
DEFAULT_UP = (0.0, 0.0, 1.0)
# The splash data set's tank floor and the checker size used there.
SPLASH_FLOOR_Z = 0.0
SPLASH_CHECKER = 0.1
# Sky gradient (bottom, top) and checker colours, sRGB 0..1 / 0..255.
SKY_BOTTOM = (0.86, 0.90, 0.95)
SKY_TOP = (0.30, 0.50, 0.78)
CHECKER_LIGHT = (214, 206, 190)
CHECKER_DARK = (92, 100, 112)
# The floor's texture, by name: its two colours. "checker" is the default;
# over it VTK's bumpy surface refracts the squares into moire. "soft" keeps
# the squares (something to see refracted) at a quarter of the contrast,
# "plain" is their mean colour and gives a refraction nothing to alias on.
CHECKER_MEAN = tuple(round((a + b) / 2) for a, b in zip(CHECKER_LIGHT, CHECKER_DARK))
FLOORS = {
    "checker": (CHECKER_LIGHT, CHECKER_DARK),
    "soft": tuple(tuple(round(m + 0.25 * (c - m)) for c, m in zip(colour, CHECKER_MEAN))
                  for colour in (CHECKER_LIGHT, CHECKER_DARK)),
    "plain": (CHECKER_MEAN, CHECKER_MEAN),
}
DEFAULT_FLOOR = "checker"
# The direction from the target to the eye when the camera frames the
# particles: the splash data set's elevated 3/4 view from -x, -y.
FRAMING_DIRECTION = (-0.8664, -1.5005, 1.2129)
CAPTIONS = ("VTK vtkOpenGLFluidMapper", "fluidcast")


def vec3(text):
    try:
        v = tuple(float(x) for x in text.split(","))
    except ValueError:
        v = ()
    if len(v) != 3 or not all(math.isfinite(x) for x in v):
        raise argparse.ArgumentTypeError(f"'{text}' is not X,Y,Z")
    return v


def size(text):
    m = re.fullmatch(r"(\d+)[xX](\d+)", text)
    if not m or int(m.group(1)) < 1 or int(m.group(2)) < 1:
        raise argparse.ArgumentTypeError(f"'{text}' is not WIDTHxHEIGHT")
    return int(m.group(1)), int(m.group(2))


def positive(text):
    try:
        v = float(text)
    except ValueError:
        v = float("nan")
    if not (v > 0 and math.isfinite(v)):
        raise argparse.ArgumentTypeError(f"'{text}' is not a positive number")
    return v


def splash_metadata(path):
    """The splash data set's frames.json entry for path, with the set's
    metadata, or None when path is not one of its frames."""
    meta_path = os.path.join(os.path.dirname(os.path.abspath(path)), "frames.json")
    try:
        with open(meta_path) as f:
            meta = json.load(f)
    except (OSError, ValueError):
        return None
    name = os.path.basename(path)
    for frame in meta.get("frames", []):
        if frame.get("file") == name and "camera" in meta:
            return meta, frame
    return None


def frame_tags(paths, splash):
    """A short unique tag per input for the output names: the splash frame
    index, else the trailing number of the file name, else the position."""
    tags = []
    for i, path in enumerate(paths):
        if splash[i] is not None:
            tags.append(f"{splash[i][1]['index']:04d}")
            continue
        m = re.search(r"(\d+)$", os.path.splitext(os.path.basename(path))[0])
        tags.append(f"{int(m.group(1)):04d}" if m else f"{i:04d}")
    if len(set(tags)) != len(tags):
        tags = [f"{i:04d}" for i in range(len(paths))]
    return tags


def frame_camera(lo, hi, width, height, fov, up):
    """Eye and target that show the whole box lo..hi from FRAMING_DIRECTION."""
    center = (lo + hi) / 2
    radius = max(float(np.linalg.norm(hi - lo)) / 2, 1e-6)
    half_v = math.radians(fov) / 2
    half_h = math.atan(math.tan(half_v) * width / height)
    distance = 1.05 * radius / math.sin(min(half_v, half_h))
    direction = np.array(FRAMING_DIRECTION) / np.linalg.norm(FRAMING_DIRECTION)
    return tuple(float(x) for x in center + distance * direction), tuple(float(x) for x in center)


def make_scene(args):
    paths = [os.path.abspath(p) for p in args.files]
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for path in paths:
        xyz = vtk_scene.load_particles_or_exit(path, PROG)
        lo, hi = np.minimum(lo, xyz.min(axis=0)), np.maximum(hi, xyz.max(axis=0))
    splash = [splash_metadata(p) for p in paths]
    is_splash = all(s is not None for s in splash)
    width, height = args.size
    radius = args.radius
    if is_splash:
        meta = splash[0][0]
        cam = meta["camera"]
        eye, target = tuple(cam["eye"]), tuple(cam["target"])
        up, fov = tuple(cam.get("up", DEFAULT_UP)), float(cam.get("fov_y_deg", DEFAULT_FOV))
        floor_z = float(meta.get("tank_bbox", {}).get("min", [0, 0, SPLASH_FLOOR_Z])[2])
        checker = SPLASH_CHECKER
        if radius is None:
            radius = float(meta["particle_radius"])
    else:
        up, fov = DEFAULT_UP, DEFAULT_FOV
        floor_z = float(lo[2])
        extent = float(max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-6))
        checker = extent / 10
        eye, target = frame_camera(lo, hi, width, height, args.fov or fov, args.up or up)
    eye, target = args.eye or eye, args.target or target
    up, fov = args.up or up, args.fov or fov
    extent = float(max(hi[0] - lo[0], hi[1] - lo[1], 1e-6))
    scene = {
        "size": [width, height],
        "eye": list(eye), "target": list(target), "up": list(up), "fov": fov,
        "radius": radius,
        "splash": is_splash,
        # A square floor 5x the data's footprint: it ends within the view of
        # the default cameras, so the sky shows above its far edge.
        "floor": {"z": floor_z, "center": [float(lo[0] + hi[0]) / 2, float(lo[1] + hi[1]) / 2],
                  "half": 2.5 * extent, "checker": checker,
                  "pattern": getattr(args, "floor", None) or DEFAULT_FLOOR},
        "data_bounds": [float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1]),
                        float(lo[2]), float(hi[2])],
        "frames": [{"tag": t, "path": p} for t, p in zip(frame_tags(paths, splash), paths)],
    }
    return scene


def checker_texture(pattern):
    from vtkmodules.vtkRenderingCore import vtkTexture
    light, dark = FLOORS[pattern]
    n = 32  # pixels per square: room for mipmaps, so the far floor does not alias
    img = np.empty((2 * n, 2 * n, 3), np.uint8)
    img[:, :] = light
    img[:n, :n] = dark
    img[n:, n:] = dark
    texture = vtkTexture()
    texture.SetInputData(vtk_scene.array_to_image(img))
    texture.RepeatOn()
    texture.InterpolateOn()
    texture.MipmapOn()
    texture.SetMaximumAnisotropicFiltering(16)
    return texture


def floor_actor(floor):
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkFiltersSources import vtkPlaneSource
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper
    (cx, cy), half, z = floor["center"], floor["half"], floor["z"]
    plane = vtkPlaneSource()
    plane.SetOrigin(cx - half, cy - half, z)
    plane.SetPoint1(cx + half, cy - half, z)
    plane.SetPoint2(cx - half, cy + half, z)
    plane.Update()
    poly = plane.GetOutput()
    xy = vtk_to_numpy(poly.GetPoints().GetData())[:, :2]
    # one texture repeat = 2x2 squares; squares aligned with the world axes
    tcoords = numpy_to_vtk((xy / (2 * floor["checker"])).astype(np.float32), deep=True)
    tcoords.SetName("TCoords")
    poly.GetPointData().SetTCoords(tcoords)
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(poly)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.SetTexture(checker_texture(floor.get("pattern", DEFAULT_FLOOR)))
    prop = actor.GetProperty()
    prop.SetAmbient(0.15)
    prop.SetDiffuse(0.85)
    prop.SetSpecular(0.0)
    return actor


def make_renderer(scene):
    from vtkmodules.vtkRenderingCore import vtkLight, vtkRenderer
    renderer = vtkRenderer()
    renderer.GradientBackgroundOn()
    renderer.SetBackground(*SKY_BOTTOM)
    renderer.SetBackground2(*SKY_TOP)
    vtk_scene.remove_frustum_culler(renderer)
    floor = scene["floor"]
    renderer.AddActor(floor_actor(floor))
    # the sun, straight above the floor (the renderer's headlight goes: a light is set)
    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetPosition(floor["center"][0], floor["center"][1], floor["z"] + 10.0)
    light.SetFocalPoint(floor["center"][0], floor["center"][1], floor["z"])
    light.SetIntensity(1.0)
    renderer.AddLight(light)
    vtk_scene.set_camera(renderer, scene["eye"], scene["target"], scene["up"], scene["fov"])
    # One clipping range for the floor image and every fluid image (floor and
    # all particles), so their backgrounds are rendered identically.
    (cx, cy), half, z = floor["center"], floor["half"], floor["z"]
    b = scene["data_bounds"]
    pad = 0.05 * max(b[1] - b[0], b[3] - b[2], b[5] - b[4], 1e-6)  # room for the spheres
    renderer.ResetCameraClippingRange(min(cx - half, b[0] - pad), max(cx + half, b[1] + pad),
                                      min(cy - half, b[2] - pad), max(cy + half, b[3] + pad),
                                      min(z, b[4] - pad), max(z, b[5] + pad))
    return renderer


def render_rgb(window):
    window.Render()
    return vtk_scene.window_rgb(window)


def write_env(scene, out):
    frames_path = os.path.join(out, "frames.tsv")
    with open(frames_path, "w") as f:
        for frame in scene["frames"]:
            f.write(f"{frame['tag']}\t{frame['path']}\n")
    csv = lambda v: ",".join(f"{x:.9g}" for x in v)  # noqa: E731
    values = {
        "EYE": csv(scene["eye"]), "TARGET": csv(scene["target"]), "UP": csv(scene["up"]),
        "FOV": f"{scene['fov']:.9g}",
        "RADIUS": "" if scene["radius"] is None else f"{scene['radius']:.9g}",
        "FLOOR": os.path.join(out, "floor.png"), "FRAMES": frames_path,
    }
    with open(os.path.join(out, "scene.env"), "w") as f:
        for key, value in values.items():
            f.write(f"{key}={shlex.quote(value)}\n")


def cmd_scene(args):
    args.out = os.path.abspath(args.out)
    os.makedirs(args.out, exist_ok=True)
    scene = make_scene(args)
    with open(os.path.join(args.out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=1)
    write_env(scene, args.out)
    renderer = make_renderer(scene)
    window = vtk_scene.make_window(renderer, *scene["size"])
    floor_png = os.path.join(args.out, "floor.png")
    vtk_scene.write_png(floor_png, render_rgb(window))
    print(f"{PROG}: GL_RENDERER {vtk_scene.gl_renderer(window)}", file=sys.stderr)
    print(floor_png)
    return 0


def caption_strip(width, height, texts):
    """A dark strip height pixels high with one caption centred over each
    width/len(texts) wide half."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkRenderingCore import vtkTextProperty
    from vtkmodules.vtkRenderingFreeType import vtkFreeTypeTools
    strip = np.full((height, width, 3), 32, np.uint8)
    part = width // len(texts)
    for i, text in enumerate(texts):
        prop = vtkTextProperty()
        prop.SetFontFamilyToArial()
        prop.SetFontSize(max(8, int(height * 0.6)))
        prop.SetColor(1.0, 1.0, 1.0)
        image = vtkImageData()
        if not vtkFreeTypeTools.GetInstance().RenderString(prop, text, 72, image):
            continue  # no font: the strip stays plain
        rgba = vtk_scene.image_to_array(image)
        rows, cols = np.nonzero(rgba[:, :, 3])
        if rows.size == 0:
            continue
        glyphs = rgba[rows.min():rows.max() + 1, cols.min():cols.max() + 1]
        gh, gw = min(glyphs.shape[0], height), min(glyphs.shape[1], part)
        glyphs = glyphs[:gh, :gw]
        y0, x0 = (height - gh) // 2, i * part + (part - gw) // 2
        alpha = glyphs[:, :, 3:4].astype(np.float32) / 255
        region = strip[y0:y0 + gh, x0:x0 + gw].astype(np.float32)
        strip[y0:y0 + gh, x0:x0 + gw] = np.round(
            region * (1 - alpha) + glyphs[:, :, :3].astype(np.float32) * alpha).astype(np.uint8)
    return strip


def compose(vtk_rgb, fc_rgb):
    """VTK | fluidcast side by side, under a caption strip."""
    h, w, _ = vtk_rgb.shape
    strip = caption_strip(2 * w, max(16, round(h * 0.05)), CAPTIONS)
    return np.concatenate([strip, np.concatenate([vtk_rgb, fc_rgb], axis=1)], axis=0)


def cmd_render(args):
    args.out = os.path.abspath(args.out)
    with open(os.path.join(args.out, "scene.json")) as f:
        scene = json.load(f)
    if args.radius is not None:
        scene["radius"] = args.radius
    if scene["radius"] is None:
        sys.exit(f"{PROG}: render: no radius (give --radius)")
    width, height = scene["size"]
    renderer = make_renderer(scene)
    mapper = vtk_scene.make_fluid_mapper(vtk_scene.points_polydata(np.zeros((1, 3), np.float32)),
                                         scene["radius"])
    renderer.AddVolume(vtk_scene.fluid_volume(mapper))
    window = vtk_scene.make_window(renderer, width, height)
    for frame in scene["frames"]:
        xyz = vtk_scene.load_particles_or_exit(frame["path"], PROG)
        mapper.SetInputData(vtk_scene.points_polydata(xyz))
        vtk_rgb = render_rgb(window)
        vtk_png = os.path.join(args.out, f"vtk_{frame['tag']}.png")
        vtk_scene.write_png(vtk_png, vtk_rgb)
        print(vtk_png)
        fc_png = os.path.join(args.out, f"fc_{frame['tag']}.png")
        try:
            fc_rgb = vtk_scene.read_png(fc_png)
        except OSError as e:
            sys.exit(f"{PROG}: {e}")
        if fc_rgb.shape != vtk_rgb.shape:
            sys.exit(f"{PROG}: {fc_png} is {fc_rgb.shape[1]}x{fc_rgb.shape[0]}, not {width}x{height}")
        compare_png = os.path.join(args.out, f"compare_{frame['tag']}.png")
        vtk_scene.write_png(compare_png, compose(vtk_rgb, fc_rgb))
        print(compare_png)
    return 0


def parse_args(argv):
    p = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    s = sub.add_parser("scene", help="pick the camera and floor, render floor.png")
    s.add_argument("--out", required=True, help="output directory")
    s.add_argument("--size", type=size, default=(960, 540), help="WIDTHxHEIGHT (default 960x540)")
    s.add_argument("--radius", type=positive, help="particle radius (default: the splash's suggestion)")
    s.add_argument("--eye", type=vec3, help="camera position X,Y,Z")
    s.add_argument("--target", type=vec3, help="point looked at X,Y,Z")
    s.add_argument("--up", type=vec3, help="up direction X,Y,Z")
    s.add_argument("--fov", type=positive, help="vertical field of view, degrees")
    s.add_argument("files", nargs="+", help=".ply or .f32 particle files")
    r = sub.add_parser("render", help="render the fluid and compose with fluidcast's images")
    r.add_argument("--out", required=True, help="the scene step's output directory")
    r.add_argument("--radius", type=positive, help="particle radius (default: scene.json's)")
    args = p.parse_args(argv)
    if args.command == "scene" and args.fov is not None and args.fov >= 180:
        p.error("--fov must be below 180 degrees")
    return args


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    return cmd_scene(args) if args.command == "scene" else cmd_render(args)


if __name__ == "__main__":
    sys.exit(main())
