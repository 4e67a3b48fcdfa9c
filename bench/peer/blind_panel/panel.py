#!/usr/bin/python3
"""panel.py - the rendering half of bench/peer/blind_panel/make_panel.sh: renders
particle frames with VTK's vtkOpenGLFluidMapper (at the settings of
vtk_best.tsv, its best look per data set) and with fluidcast (its built-in
scene, and over VTK's floor image), and composes blind "A | B" pairs.

    panel.py pairs --out DIR --seed N --fluidcast BIN --server HOST:PORT FILE...
        DIR/renders/  every image, named by what made it (never shown to judges)
        DIR/pairs/    pair_NN.png ("A | B", or "A | B | Reference") and BRIEF.md
        DIR/key.tsv   which side is which, the seed, the settings (outside pairs/)
    panel.py sweep --out DIR --scales 1,1.5,2,3 --filters narrow,bilateral FILE...
        VTK alone at each radius scale x filter: DIR/sweep/TAG_xSCALE_FILTER.png

Both render with VTK, so both need an X display:
    xvfb-run -a env LIBGL_ALWAYS_SOFTWARE=1 /usr/bin/python3 panel.py ...
Needs Debian's python3-vtk9 (VTK 9.1) and python3-numpy.
"""
import argparse
import json
import os
import random
import re
import subprocess
import sys
from collections import OrderedDict
from types import SimpleNamespace

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import vtk_fluid_image  # noqa: E402
import vtk_scene  # noqa: E402

PROG = "panel"
PRESETS = os.path.join(HERE, "vtk_best.tsv")
BRIEF = os.path.join(HERE, "judge_brief.md")
REFERENCE = os.path.join(os.path.dirname(HERE), "reference_render.sh")
# What a pair may show, each a way of rendering a frame.
CONDITIONS = ("vtk", "fc_floor", "fc_builtin")
# The default comparisons: fluidcast over VTK's own floor (only the fluid
# differs), and fluidcast in its built-in scene (each renderer's whole look).
DEFAULT_COMPARISONS = ("vtk:fc_floor", "vtk:fc_builtin")
GUTTER = 6          # dark pixels between the images of a pair
STEP_TIMEOUT = int(os.environ.get("STEP_TIMEOUT", "600"))


def die(message):
    sys.exit(f"{PROG}: {message}")


# --- data sets -------------------------------------------------------------

def sidecar(path):
    """gen_particles.py's JSON next to a .f32 file, or None."""
    json_path = os.path.splitext(path)[0] + ".json"
    try:
        with open(json_path) as f:
            meta = json.load(f)
    except (OSError, ValueError):
        return None
    return meta if isinstance(meta, dict) else None


def data_set(path):
    """(kind, base radius) of a particle file: kind names its row in
    vtk_best.tsv; the base radius is the data's own suggested render radius
    (None: fluidcast estimates one)."""
    splash = vtk_fluid_image.splash_metadata(path)
    if splash is not None:   # a set with a frames.json like the splash's names its kind there
        return str(splash[0].get("scene", "splash")), float(splash[0]["particle_radius"])
    meta = sidecar(path)
    if meta is not None and "scene" in meta:
        radius = meta.get("suggested_render_radius", meta.get("particle_radius"))
        return str(meta["scene"]), (float(radius) if radius is not None else None)
    return "other", None


def read_presets():
    """vtk_best.tsv: kind -> (radius scale, filter)."""
    presets = {}
    with open(PRESETS) as f:
        for number, line in enumerate(f, 1):
            words = line.split("#", 1)[0].split()
            if not words:
                continue
            if len(words) != 3 or words[2] not in ("narrow", "bilateral"):
                die(f"{PRESETS}:{number}: want 'KIND SCALE narrow|bilateral'")
            presets[words[0]] = (float(words[1]), words[2])
    if "other" not in presets:
        die(f"{PRESETS}: no 'other' row (the default)")
    return presets


def group_files(files):
    """The files grouped by data set (kind, folder and suggested radius: the
    same scene at another resolution is another set), in order: each group
    shares one camera, floor and radius."""
    groups = OrderedDict()
    for path in files:
        path = os.path.abspath(path)
        kind, radius = data_set(path)
        key = (kind, os.path.dirname(path), radius)
        groups.setdefault(key, {"kind": kind, "radius": radius, "files": []})["files"].append(path)
    for i, group in enumerate(groups.values()):
        group["name"] = f"{i:02d}_{group['kind']}"
    return list(groups.values())


# --- VTK -------------------------------------------------------------------

def make_vtk_scene(group, size, out, camera, floor):
    """vtk_fluid_image's scene for a group (camera, floor), and its floor image."""
    args = SimpleNamespace(files=group["files"], size=size, radius=group["radius"], floor=floor, **camera)
    scene = vtk_fluid_image.make_scene(args)
    os.makedirs(out, exist_ok=True)
    renderer = vtk_fluid_image.make_renderer(scene)
    window = vtk_scene.make_window(renderer, *scene["size"])
    floor_png = os.path.join(out, f"floor_{group['name']}.png")
    vtk_scene.write_png(floor_png, vtk_fluid_image.render_rgb(window))
    scene["floor_png"] = floor_png
    return scene


def configure_mapper(mapper, radius, filter_name):
    """VTK 9.1's Python offers the filter's kind, not its iterations or
    width (VTK filters 3 times, 5 pixels wide); the rest is VTK's own."""
    from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLFluidMapper
    mapper.SetParticleRadius(radius)
    method = vtkOpenGLFluidMapper.NarrowRange if filter_name == "narrow" else \
        vtkOpenGLFluidMapper.BilateralGaussian
    mapper.SetSurfaceFilterMethod(method)


class VtkRenderer:
    """VTK's fluid over the scene's floor, re-configurable between frames."""

    def __init__(self, scene):
        self.renderer = vtk_fluid_image.make_renderer(scene)
        empty = vtk_scene.points_polydata(np.zeros((1, 3), np.float32))
        self.mapper = vtk_scene.make_fluid_mapper(empty, 1.0)
        self.renderer.AddVolume(vtk_scene.fluid_volume(self.mapper))
        self.window = vtk_scene.make_window(self.renderer, *scene["size"])

    def render(self, path, radius, filter_name, png):
        configure_mapper(self.mapper, radius, filter_name)
        self.mapper.SetInputData(vtk_scene.points_polydata(vtk_scene.load_particles_or_exit(path, PROG)))
        vtk_scene.write_png(png, vtk_fluid_image.render_rgb(self.window))


# --- fluidcast and the reference ------------------------------------------

def csv(v):
    return ",".join(f"{x:.9g}" for x in v)


def camera_args(scene):
    w, h = scene["size"]
    return ["--size", f"{w}x{h}", "--eye", csv(scene["eye"]), "--target", csv(scene["target"]),
            "--up", csv(scene["up"]), "--fov", f"{scene['fov']:.9g}"]


def run_step(command, what):
    try:
        done = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                              timeout=STEP_TIMEOUT)
    except subprocess.TimeoutExpired:
        die(f"{what}: no result within {STEP_TIMEOUT} s")
    if done.returncode != 0:
        sys.stderr.write(done.stdout + done.stderr)
        die(f"{what} failed (exit {done.returncode})")
    return done.stdout + done.stderr


def fluidcast(args, scene, path, radius, background, png):
    command = [args.fluidcast, "snapshot", path, "-o", png, "--server", args.server] + camera_args(scene)
    if radius is not None:
        command += ["--radius", f"{radius:.9g}"]
    if background:
        command += ["--background", scene["floor_png"]]
    output = run_step(command + args.fluidcast_args, f"fluidcast snapshot {path}")
    if radius is None:   # the estimate, for VTK and the rest of the group
        m = re.search(r"radius ([0-9.eE+-]+) \(estimated", output)
        if not m:
            die(f"no 'radius R (estimated ...)' in fluidcast's output for {path}")
        radius = float(m.group(1))
    return radius


def reference(scene, path, radius, png):
    run_step([REFERENCE, path, "-o", png, "--radius", f"{radius:.9g}"] + camera_args(scene),
             f"reference render of {path}")


# --- pairs -----------------------------------------------------------------

def compose(images, labels):
    """The images side by side with a dark gutter, under a label strip."""
    h, w, _ = images[0].shape
    gutter = np.full((h, GUTTER, 3), 32, np.uint8)
    strip_h = max(16, round(h * 0.05))
    strips, row = [], []
    for i, (image, label) in enumerate(zip(images, labels)):
        if i:
            strips.append(np.full((strip_h, GUTTER, 3), 32, np.uint8))
            row.append(gutter)
        strips.append(vtk_fluid_image.caption_strip(w, strip_h, (label,)))
        row.append(image)
    return np.concatenate([np.concatenate(strips, axis=1), np.concatenate(row, axis=1)], axis=0)


def parse_comparisons(text):
    comparisons = []
    for item in text.split(","):
        sides = tuple(item.split(":"))
        if len(sides) != 2 or sides[0] == sides[1] or not all(s in CONDITIONS for s in sides):
            die(f"--comparisons: '{item}' is not X:Y with X, Y two of {', '.join(CONDITIONS)}")
        comparisons.append(sides)
    return comparisons


def render_once(args, png, render):
    """render() makes png, unless --reuse-renders finds it made already."""
    if args.reuse_renders and os.path.exists(png):
        print(f"{PROG}: reusing {png}", file=sys.stderr)
        return
    render()


def render_all(args, groups, presets, renders):
    """Every image the pairs need; returns one record per frame."""
    frames = []
    for group in groups:
        scene = make_vtk_scene(group, args.size, renders, camera_options(args), args.floor)
        scale, filter_name = presets.get(group["kind"], presets["other"])
        scale = args.vtk_scale or scale
        filter_name = args.vtk_filter or filter_name
        radius = args.radius or group["radius"]
        vtk = VtkRenderer(scene)
        for frame in scene["frames"]:
            stem = f"{group['name']}_{frame['tag']}"
            record = {"path": frame["path"], "kind": group["kind"], "images": {}}
            out = {c: os.path.join(renders, f"{c}_{stem}.png") for c in CONDITIONS}
            print(f"{PROG}: {frame['path']}", file=sys.stderr)
            if radius is None:   # fluidcast's estimate, for VTK and the rest of the group
                radius = fluidcast(args, scene, frame["path"], None, False, out["fc_builtin"])
            path, r = frame["path"], radius
            render_once(args, out["fc_builtin"], lambda: fluidcast(args, scene, path, r, False, out["fc_builtin"]))
            render_once(args, out["fc_floor"], lambda: fluidcast(args, scene, path, r, True, out["fc_floor"]))
            render_once(args, out["vtk"], lambda: vtk.render(path, scale * r, filter_name, out["vtk"]))
            if args.reference:
                out["reference"] = os.path.join(renders, f"reference_{stem}.png")
                render_once(args, out["reference"], lambda: reference(scene, path, r, out["reference"]))
            record["images"] = out
            record["radius"] = radius
            record["vtk"] = f"radius {scale * radius:.6g} ({scale:g}x) {filter_name}"
            frames.append(record)
    return frames


def write_pairs(args, frames, comparisons):
    rng = random.Random(args.seed)
    pairs = [(frame, sides) for frame in frames for sides in comparisons]
    rng.shuffle(pairs)
    pairs_dir = os.path.join(args.out, "pairs")
    os.makedirs(pairs_dir, exist_ok=True)
    width = max(2, len(str(len(pairs))))
    key_lines = [
        "# Blind panel key: which condition each pair shows left (A) and right (B).",
        "# Do not give this file to judges. Conditions: vtk = VTK's vtkOpenGLFluidMapper over",
        "# its floor; fc_floor = fluidcast over the same floor image (--background);",
        "# fc_builtin = fluidcast in its own built-in scene. Scorer: bench/peer/blind_panel/score.py",
        f"seed\t{args.seed}",
        f"reference\t{'yes' if args.reference else 'no'}",
        f"floor\t{args.floor}",
        "pair\tA\tB\tframe\tvtk_settings\tfluidcast_radius",
    ]
    for i, (frame, sides) in enumerate(pairs, 1):
        name = f"pair_{i:0{width}d}"
        if rng.random() < 0.5:
            sides = (sides[1], sides[0])
        images = [vtk_scene.read_png(frame["images"][c]) for c in sides]
        labels = ["A", "B"]
        if args.reference:
            images.append(vtk_scene.read_png(frame["images"]["reference"]))
            labels.append("Reference")
        vtk_scene.write_png(os.path.join(pairs_dir, f"{name}.png"), compose(images, labels))
        key_lines.append("\t".join([name, sides[0], sides[1], frame["path"], frame["vtk"],
                                    f"{frame['radius']:.6g}"]))
    with open(os.path.join(args.out, "key.tsv"), "w") as f:
        f.write("\n".join(key_lines) + "\n")
    with open(BRIEF) as f:
        brief = f.read()
    brief = brief.replace("{PAIRS}", str(len(pairs))).replace("{LAST}", f"pair_{len(pairs):0{width}d}")
    with open(os.path.join(pairs_dir, "BRIEF.md"), "w") as f:
        f.write(brief)
    print(os.path.join(args.out, "key.tsv"))
    print(pairs_dir)


def camera_options(args):
    return {"eye": args.eye, "target": args.target, "up": args.up, "fov": args.fov}


def cmd_pairs(args):
    args.out = os.path.abspath(args.out)
    renders = os.path.join(args.out, "renders")
    os.makedirs(renders, exist_ok=True)
    comparisons = parse_comparisons(args.comparisons)
    frames = render_all(args, group_files(args.files), read_presets(), renders)
    write_pairs(args, frames, comparisons)
    return 0


def cmd_sweep(args):
    out = os.path.join(os.path.abspath(args.out), "sweep")
    scales = [vtk_fluid_image.positive(s) for s in args.scales.split(",")]
    filters = args.filters.split(",")
    if not all(f in ("narrow", "bilateral") for f in filters):
        die("--filters: narrow and/or bilateral")
    for group in group_files(args.files):
        radius = args.radius or group["radius"]
        if radius is None:
            die(f"{group['files'][0]}: no suggested radius in the data set: give --radius")
        scene = make_vtk_scene(group, args.size, out, camera_options(args), args.floor)
        vtk = VtkRenderer(scene)
        for frame in scene["frames"]:
            for scale in scales:
                for filter_name in filters:
                    png = os.path.join(out, f"{group['name']}_{frame['tag']}_x{scale:g}_{filter_name}.png")
                    vtk.render(frame["path"], scale * radius, filter_name, png)
                    print(png)
    return 0


def parse_args(argv):
    p = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)

    def common(s):
        s.add_argument("--out", required=True, help="output directory")
        s.add_argument("--size", type=vtk_fluid_image.size, default=(960, 540), help="WIDTHxHEIGHT per image")
        s.add_argument("--radius", type=vtk_fluid_image.positive,
                       help="base particle radius (default: the data set's suggestion)")
        s.add_argument("--eye", type=vtk_fluid_image.vec3)
        s.add_argument("--target", type=vtk_fluid_image.vec3)
        s.add_argument("--up", type=vtk_fluid_image.vec3)
        s.add_argument("--fov", type=vtk_fluid_image.positive)
        s.add_argument("--floor", choices=sorted(vtk_fluid_image.FLOORS), default=vtk_fluid_image.DEFAULT_FLOOR,
                       help="VTK's floor texture, also fc_floor's background (default checker)")
        s.add_argument("files", nargs="+", help=".ply or .f32 particle files")

    s = sub.add_parser("pairs", help="render and compose blind pairs")
    common(s)
    s.add_argument("--seed", type=int, required=True, help="randomisation seed (goes in the key)")
    s.add_argument("--fluidcast", required=True, help="the fluidcast CLI")
    s.add_argument("--server", required=True, help="a running fluidcastd, HOST:PORT")
    s.add_argument("--comparisons", default=",".join(DEFAULT_COMPARISONS))
    s.add_argument("--reference", action="store_true", help="add the path-traced reference as a third image")
    s.add_argument("--vtk-scale", type=vtk_fluid_image.positive, help="override vtk_best.tsv's radius scale")
    s.add_argument("--vtk-filter", choices=("narrow", "bilateral"), help="override vtk_best.tsv's filter")
    s.add_argument("--fluidcast-args", default="", help="extra `fluidcast snapshot` options, one string")
    s.add_argument("--reuse-renders", action="store_true",
                   help="keep the images already in OUT/renders (same files and options only)")
    w = sub.add_parser("sweep", help="VTK alone at several radius scales and filters")
    common(w)
    w.add_argument("--scales", default="1,1.5,2,3")
    w.add_argument("--filters", default="narrow,bilateral")
    args = p.parse_args(argv)
    if args.command == "pairs":
        args.fluidcast_args = args.fluidcast_args.split()
    return args


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    return cmd_pairs(args) if args.command == "pairs" else cmd_sweep(args)


if __name__ == "__main__":
    sys.exit(main())
