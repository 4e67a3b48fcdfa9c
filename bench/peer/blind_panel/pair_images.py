#!/usr/bin/python3
"""pair_images.py - a blind panel of images already rendered: two (or more)
conditions of the same frames, e.g. fluidcast before and after a look change.

    pair_images.py --out DIR --seed N NAME=DIR NAME=DIR [NAME=DIR...]

Each NAME=DIR is a condition: a folder of PNGs, the same file names in every
folder (one per frame, the same camera and size). For each frame and each two
conditions the script writes one "A | B" pair, sides and order shuffled from
--seed, into DIR/pairs/ with the judges' brief, and the key to DIR/key.tsv,
in make_panel.sh's format, so that score.py tallies the answers.
Needs Debian's python3-vtk9 (the label strip) and python3-numpy.
"""
import argparse
import itertools
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))
import panel  # noqa: E402
import vtk_scene  # noqa: E402


def conditions(items):
    out = []
    for item in items:
        name, sep, folder = item.partition("=")
        if not sep or not name or not os.path.isdir(folder):
            sys.exit(f"pair_images: '{item}' is not NAME=FOLDER")
        out.append((name, folder))
    if len(out) < 2:
        sys.exit("pair_images: needs at least two conditions")
    return out


def frames_of(conds):
    names = [sorted(f for f in os.listdir(d) if f.endswith(".png")) for _, d in conds]
    common = sorted(set(names[0]).intersection(*names[1:]))
    if not common:
        sys.exit("pair_images: the folders share no PNG file name")
    return common


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", required=True)
    p.add_argument("--seed", type=int, required=True)
    p.add_argument("condition", nargs="+", help="NAME=FOLDER")
    args = p.parse_args()
    conds = conditions(args.condition)
    frames = frames_of(conds)
    rng = random.Random(args.seed)
    pairs = [(f, a, b) for f in frames for a, b in itertools.combinations(conds, 2)]
    rng.shuffle(pairs)
    pairs_dir = os.path.join(args.out, "pairs")
    os.makedirs(pairs_dir, exist_ok=True)
    width = max(2, len(str(len(pairs))))
    key = ["# Blind panel key (pair_images.py): which condition each pair shows left (A) and right (B).",
           "# Do not give this file to judges. Scorer: bench/peer/blind_panel/score.py",
           f"seed\t{args.seed}", "pair\tA\tB\tframe"]
    # Sides balanced, not coin-flipped: a coin put one condition on A in 6 of
    # 7 pairs once, and a judge who favours a side then reads as a verdict.
    swaps = [i % 2 == 1 for i in range(len(pairs))]
    rng.shuffle(swaps)
    for i, ((frame, a, b), swap) in enumerate(zip(pairs, swaps), 1):
        if swap:
            a, b = b, a
        name = f"pair_{i:0{width}d}"
        images = [vtk_scene.read_png(os.path.join(d, frame)) for _, d in (a, b)]
        vtk_scene.write_png(os.path.join(pairs_dir, f"{name}.png"), panel.compose(images, ["A", "B"]))
        key.append("\t".join([name, a[0], b[0], frame]))
    with open(os.path.join(args.out, "key.tsv"), "w") as f:
        f.write("\n".join(key) + "\n")
    with open(panel.BRIEF) as f:
        brief = f.read()
    with open(os.path.join(pairs_dir, "BRIEF.md"), "w") as f:
        f.write(brief.replace("{PAIRS}", str(len(pairs))).replace("{LAST}", f"pair_{len(pairs):0{width}d}"))
    print(os.path.join(args.out, "key.tsv"))


if __name__ == "__main__":
    main()
