#!/usr/bin/python3
"""The verdict set out of a simulated sequence: copies the six frames named in params.json's
"verdict_frames" (time and what the frame shows) from simulate.py's output folder into the verdict
folder, with a frames.json that lists those frames alone. The files keep their sequence names
(frame_NNNN.ply, NNNN the index in the sequence), so a frame is the same bytes in both folders.
The camera is params.json's (simulate.camera_for), so it can be set after the run."""
import argparse
import json
import os
import shutil
import sys

import numpy as np

from simulate import camera_for, look_at_fraction_outside


def positions(path):
    raw = open(path, "rb").read()
    body = raw.index(b"end_header\n") + len(b"end_header\n")
    return np.frombuffer(raw, dtype="<f4", offset=body).reshape(-1, 7)[:, :3].astype(np.float64)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--params", default=os.path.join(here, "params.json"))
    ap.add_argument("--sequence", required=True, help="simulate.py's --out folder")
    ap.add_argument("--out", required=True, help="the verdict folder")
    args = ap.parse_args()
    params = json.load(open(args.params))
    wanted = params["verdict_frames"]
    camera = camera_for(params)
    meta = json.load(open(os.path.join(args.sequence, "frames.json")))
    by_time = {round(f["time"], 6): f for f in meta["frames"]}
    chosen = []
    for time, note in wanted:
        frame = by_time.get(round(time, 6))
        if frame is None:
            sys.exit(f"select_frames: no frame at t={time} s in {args.sequence} (frame_times in params.json)")
        chosen.append(dict(frame, what=note))
    os.makedirs(args.out, exist_ok=True)
    for frame in chosen:
        shutil.copyfile(os.path.join(args.sequence, frame["file"]), os.path.join(args.out, frame["file"]))
        x = positions(os.path.join(args.out, frame["file"]))
        frame["fraction_outside_view_16x9"] = look_at_fraction_outside(x, camera, 16.0 / 9.0)
        frame["fraction_outside_view_4x3"] = look_at_fraction_outside(x, camera, 4.0 / 3.0)
    lo = [min(f["data_bbox"]["min"][a] for f in chosen) for a in range(3)]
    hi = [max(f["data_bbox"]["max"][a] for f in chosen) for a in range(3)]
    meta["parameters"].update(camera=params["camera"], verdict_frames=wanted, wall_height=params["wall_height"])
    meta["tank_bbox"]["max"][2] = params["wall_height"]
    meta.update(scene="verdict_dambreak", camera=camera, frame_count=len(chosen), frames=chosen,
                bbox={"min": lo, "max": hi, "note": "union of particle-centre bounding boxes over these frames"})
    with open(os.path.join(args.out, "frames.json"), "w") as fh:
        json.dump(meta, fh, indent=1)
    for frame in chosen:
        print(f"{frame['file']}  t={frame['time']:.2f} s  {frame['what']}")


if __name__ == "__main__":
    sys.exit(main())
