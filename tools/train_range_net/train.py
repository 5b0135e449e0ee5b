#!/usr/bin/python3
"""Trains the project's range-image segmentation network on simulated scans (run by hand).

Usage (config/models/README.md has the exact command that made the committed model):
  tools/train_range_net/make_data.sh runs/range_net/train train
  tools/train_range_net/make_data.sh runs/range_net/heldout heldout
  tools/train_range_net/make_data.sh runs/range_net/kitti kitti
  /usr/bin/python3 tools/train_range_net/train.py --train runs/range_net/train \
      --heldout runs/range_net/heldout --out runs/range_net/model --minutes 44 \
      --extra runs/range_net/kitti:5 --pole-weight 2 --realism 1 --rare-crop 0.25

Debian's python3-torch on the CPU, one thread, fixed seeds. Input: the spherical projection of
lib/frontend/range_image.h (the same formula; keep them in step), channels range, x, y, z
(no remission: the simulator's intensity is a function of the class, a cue real scans do not
give), 64 rows, width 1024 (training on random 512-column crops; the network is fully
convolutional). Each sample is augmented in point space: sensor tilt (roll, pitch +-3 deg),
mounting height +-0.25 m, yaw, mirror, extra range noise, dropout of up to 15 % of points;
with --realism, first the traits of a real sensor that the simulator leaves out
(sensor_traits: beam elevation jitter, range-dependent noise, per-beam and range-dependent
missing returns, mixed pixels at depth edges). The options' defaults are the first model's
recipe (2026-12-02).
Writes slide_range_net.onnx (opset 11) and slide_range_net.yaml (projection, normalisation,
classes) and prints per-class pixel IoU on the held-out scans.
"""
import argparse
import glob
import math
import os
import random
import sys
import time

import numpy as np
import torch
import torch.nn as nn
import torch.nn.functional as F

# Model classes: name, SemanticKITTI label written to points, SemanticKITTI labels that mean it.
CLASSES = [
    ("unlabeled", 0, []),
    ("car", 10, [10, 252]),
    ("trunk", 71, [71]),
    ("pole", 80, [80, 81]),
    ("vegetation", 70, [70]),
    ("ground", 40, [40, 44, 48, 49, 60, 72]),
    ("structure", 50, [50, 51, 52]),
    ("chair", 100, [100]),
    ("table", 101, [101]),
    ("monitor", 102, [102]),
    ("other-object", 99, [99]),
]
FOV = {"os1-64": (16.6, -16.6), "hdl-64e": (3.0, -25.0)}
HEIGHT, WIDTH, CROP = 64, 1024, 512


def label_lut():
    lut = np.zeros(65536, dtype=np.int64)
    for k, (_, _, labels) in enumerate(CLASSES):
        for l in labels:
            lut[l] = k
    return lut


LUT = label_lut()


def read_scan(bin_path):
    pts = np.fromfile(bin_path, dtype=np.float32).reshape(-1, 4)[:, :3]
    lab_path = bin_path.replace("/velodyne/", "/labels/").replace(".bin", ".label")
    lab = np.fromfile(lab_path, dtype=np.uint32) & 0xFFFF
    if len(lab) != len(pts):
        raise ValueError(f"{lab_path}: {len(lab)} labels for {len(pts)} points")
    return pts, LUT[lab].astype(np.uint8)


def sensor_of(robot_dir):
    yaml = open(os.path.join(robot_dir, "robot.yaml")).read()
    return "hdl-64e" if "hdl-64e" in yaml else "os1-64"


def load_set(root, limit=None, stride=1):
    """[(points, classes, sensor, run)] of every scan under root (one folder per simulated run, one
    sub-folder per robot); every stride-th scan of each robot (KITTI worlds record at 10 Hz)."""
    out = []
    for run in sorted(glob.glob(os.path.join(root, "*"))):
        for robot in sorted(glob.glob(os.path.join(run, "robot*"))):
            bins = sorted(glob.glob(os.path.join(robot, "velodyne", "*.bin")))[::stride]
            if not bins:
                continue
            sensor = sensor_of(robot) if os.path.exists(os.path.join(robot, "robot.yaml")) else "os1-64"
            if "hdl-64e" in os.path.basename(run):
                sensor = "hdl-64e"
            for b in bins[:limit]:
                p, c = read_scan(b)
                out.append((p, c, sensor, os.path.basename(run)))
    return out


def project(pts, cls, fov_up, fov_down, height=HEIGHT, width=WIDTH):
    """Range image (4, H, W: range, x, y, z) and per-pixel class, nearest point per pixel."""
    r = np.linalg.norm(pts, axis=1)
    ok = np.isfinite(r) & (r > 0)
    pts, cls, r = pts[ok], cls[ok], r[ok]
    up, down = math.radians(fov_up), math.radians(fov_down)
    yaw = np.arctan2(pts[:, 1], pts[:, 0])
    pitch = np.arcsin(np.clip(pts[:, 2] / r, -1, 1))
    u = np.clip(np.floor(0.5 * (1 - yaw / math.pi) * width), 0, width - 1).astype(np.int64)
    v = np.clip(np.floor((1 - (pitch - down) / (up - down)) * height), 0, height - 1).astype(np.int64)
    order = np.argsort(-r)  # far first: nearer points overwrite
    px = v[order] * width + u[order]
    img = np.zeros((4, height * width), dtype=np.float32)
    lab = np.zeros(height * width, dtype=np.int64)
    mask = np.zeros(height * width, dtype=bool)
    img[0, px] = r[order]
    img[1:, px] = pts[order].T
    lab[px] = cls[order]
    mask[px] = True
    return img.reshape(4, height, width), lab.reshape(height, width), mask.reshape(height, width)


def uniform_beams(n, up, down):
    return np.linspace(up, down, n)


# The simulator's beam tables (lib/simulator/lidar.cpp), top to bottom, degrees.
BEAMS = {"os1-64": uniform_beams(64, 16.6, -16.6),
         "hdl-64e": np.concatenate([uniform_beams(32, 2.0, -8.33), uniform_beams(32, -8.83, -24.9)])}


def sensor_traits(pts, cls, sensor, rng, realism):
    """Traits of a real spinning LiDAR the simulator leaves out, scaled by realism (0: none),
    applied in the sensor frame before the mounting is randomised:
    - beam elevation jitter: each beam's elevation off its nominal value by N(0, s), s up to
      0.15 deg (a real unit's per-laser calibration is not the datasheet's even spacing);
    - range-dependent noise: sigma = s0 + s1 r, s0 up to 2 cm (HDL-64E datasheet: < 2 cm),
      s1 up to 2 cm per 100 m (beam footprint and weak returns grow with range);
    - missing returns: per-beam loss (a few weak lasers lose 30-100 % of their returns, the
      others up to 10 %) and a range-dependent loss up to 30 % at 80 m;
    - mixed pixels: where two azimuth neighbours of one beam differ by > 0.5 m, the far
      return of up to half of the pairs is moved between the two surfaces, as a beam that
      straddles an edge returns an average; such points get no label (not scored, not taught).
    Returns points, classes and a keep mask."""
    n = len(pts)
    if realism <= 0 or n == 0:
        return pts, cls, np.ones(n, dtype=bool)
    r = np.linalg.norm(pts, axis=1)
    r = np.maximum(r, 1e-6)
    pitch = np.degrees(np.arcsin(np.clip(pts[:, 2] / r, -1, 1)))
    yaw = np.arctan2(pts[:, 1], pts[:, 0])
    table = BEAMS[sensor]
    beam = np.searchsorted(-(table[:-1] + table[1:]) / 2, -pitch)  # nearest beam of the descending table
    nb = len(table)
    pitch = pitch + rng.normal(0, rng.uniform(0, 0.15 * realism), nb)[beam]
    sigma = rng.uniform(0, 0.02 * realism) + rng.uniform(0, 2e-4 * realism) * r
    r = r + sigma * rng.standard_normal(n)
    cls = cls.copy()
    # Mixed pixels along each beam (sorted by azimuth).
    order = np.lexsort((yaw, beam))
    rs, bs = r[order], beam[order]
    a, b = order[:-1], order[1:]
    edge = (bs[1:] == bs[:-1]) & (np.abs(rs[1:] - rs[:-1]) > 0.5)
    edge &= rng.random(len(edge)) < rng.uniform(0, 0.5 * realism)
    a, b = a[edge], b[edge]
    far = np.where(r[a] > r[b], a, b)
    near = np.where(r[a] > r[b], b, a)
    t = rng.uniform(0.1, 0.9, len(far))
    r[far] = r[near] + t * (r[far] - r[near])
    cls[far] = 0
    p = np.radians(pitch)
    q = np.stack([r * np.cos(p) * np.cos(yaw), r * np.cos(p) * np.sin(yaw), r * np.sin(p)], 1).astype(np.float32)
    weak = rng.random(nb) < 0.1 * realism
    loss = np.where(weak, rng.uniform(0.3, 1.0, nb), rng.uniform(0, 0.1 * realism, nb))
    p_lost = loss[beam] + rng.uniform(0, 0.3 * realism) * np.minimum(r / 80.0, 1.0) ** 2
    keep = rng.random(n) >= p_lost
    return q, cls, keep


def augment(pts, rng, height=0.25):
    roll, pitch, yaw = rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-180, 180)
    cr, sr, cp, sp = math.cos(math.radians(roll)), math.sin(math.radians(roll)), math.cos(math.radians(pitch)), math.sin(math.radians(pitch))
    cy, sy = math.cos(math.radians(yaw)), math.sin(math.radians(yaw))
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    Ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    q = pts @ (Rz @ Ry @ Rx).T.astype(np.float32)
    if rng.random() < 0.5:
        q[:, 1] = -q[:, 1]
    q[:, 2] += rng.uniform(-height, height)
    r = np.linalg.norm(q, axis=1, keepdims=True)
    q *= (r + rng.uniform(0, 0.03) * rng.standard_normal(r.shape).astype(np.float32)) / np.maximum(r, 1e-6)
    keep = rng.random(len(q)) >= rng.uniform(0, 0.15)
    return q.astype(np.float32), keep


class Block(nn.Sequential):
    def __init__(self, cin, cout, stride=1, dilation=1, k=3):
        pad = dilation * (k // 2)
        super().__init__(nn.Conv2d(cin, cout, k, stride, pad, dilation, bias=False), nn.BatchNorm2d(cout), nn.ReLU(inplace=True))


class RangeNet(nn.Module):
    """Encoder (1, 1/2, 1/4, 1/8 resolution) and a decoder with skip connections."""

    def __init__(self, cin, k):
        super().__init__()
        self.stem = Block(cin, 16)
        self.enc1 = nn.Sequential(Block(16, 24, 2), Block(24, 24))
        self.enc2 = nn.Sequential(Block(24, 48, 2), Block(48, 48))
        self.enc3 = nn.Sequential(Block(48, 96, 2), Block(96, 96), Block(96, 96, dilation=2))
        self.dec2 = nn.Sequential(Block(96 + 48, 48, k=1), Block(48, 48))
        self.dec1 = nn.Sequential(Block(48 + 24, 24, k=1), Block(24, 24))
        self.dec0 = Block(24 + 16, 16, k=1)
        self.head = nn.Conv2d(16, k, 1)

    def forward(self, x):
        s0 = self.stem(x)
        s1 = self.enc1(s0)
        s2 = self.enc2(s1)
        s3 = self.enc3(s2)
        up = lambda t: F.interpolate(t, scale_factor=2.0, mode="nearest")
        d2 = self.dec2(torch.cat([up(s3), s2], 1))
        d1 = self.dec1(torch.cat([up(d2), s1], 1))
        d0 = self.dec0(torch.cat([up(d1), s0], 1))
        return self.head(d0)


def sample(data, rng, aug=True, crop=CROP, realism=0.0, rare_crop=0.0, rare=3):
    pts, cls, sensor, _ = data[rng.integers(len(data))]
    if aug:
        pts, cls, keep = sensor_traits(pts, cls, sensor, rng, realism)
        pts, cls = pts[keep], cls[keep]
        pts, keep = augment(pts, rng)
        pts, cls = pts[keep], cls[keep]
    img, lab, mask = project(pts, cls, *FOV[sensor])
    c0 = rng.integers(0, WIDTH - crop + 1)
    if rare_crop > 0 and rng.random() < rare_crop:  # centre the crop on a rare-class pixel, if any
        cols = np.nonzero((lab == rare).any(0))[0]
        if len(cols):
            c0 = int(np.clip(cols[rng.integers(len(cols))] - crop // 2, 0, WIDTH - crop))
    return img[:, :, c0:c0 + crop], lab[:, c0:c0 + crop], mask[:, c0:c0 + crop]


def normalise(img, mask, means, stds):
    return np.where(mask[None], (img - means[:, None, None]) / stds[:, None, None], 0).astype(np.float32)


def iou_table(conf):
    out = {}
    for k, (name, _, _) in enumerate(CLASSES):
        if k == 0:
            continue
        tp, fp, fn = conf[k, k], conf[:, k].sum() - conf[k, k], conf[k, :].sum() - conf[k, k]
        if tp + fn > 0:
            out[name] = tp / (tp + fp + fn)
    return out


def evaluate(net, data, means, stds):
    net.eval()
    conf = np.zeros((len(CLASSES), len(CLASSES)), dtype=np.int64)  # truth x prediction
    with torch.no_grad():
        for pts, cls, sensor, _ in data:
            img, lab, mask = project(pts, cls, *FOV[sensor])
            x = torch.from_numpy(normalise(img, mask, means, stds))[None]
            pred = net(x)[0].argmax(0).numpy()
            t, p = lab[mask & (lab > 0)], pred[mask & (lab > 0)]
            np.add.at(conf, (t, p), 1)
    net.train()
    return iou_table(conf)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--train", required=True)
    ap.add_argument("--heldout", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--minutes", type=float, default=25.0, help="wall-clock training budget")
    ap.add_argument("--batch", type=int, default=6)
    ap.add_argument("--seed", type=int, default=19)
    ap.add_argument("--limit", type=int, default=None, help="scans per run (a quick smoke test)")
    ap.add_argument("--extra", nargs="*", default=[], help="more training roots, each ROOT:STRIDE (every STRIDE-th scan)")
    ap.add_argument("--heldout-limit", type=int, default=8, help="held-out scans per run and robot")
    ap.add_argument("--pole-weight", type=float, default=1.0, help="extra factor on the pole class weight")
    ap.add_argument("--realism", type=float, default=0.0, help="scale of the real-sensor traits (sensor_traits; 0: off)")
    ap.add_argument("--rare-crop", type=float, default=0.0, help="share of crops centred on a pole pixel")
    args = ap.parse_args()
    torch.set_num_threads(1)
    torch.manual_seed(args.seed)
    random.seed(args.seed)
    rng = np.random.default_rng(args.seed)

    train = load_set(args.train, args.limit)
    for spec in args.extra:
        root, _, stride = spec.partition(":")
        more = load_set(root, args.limit, int(stride or 1))
        print(f"{len(more)} extra training scans from {root}", flush=True)
        train += more
    heldout = load_set(args.heldout, limit=args.limit or args.heldout_limit)
    print(f"{len(train)} training scans, {len(heldout)} held-out scans", flush=True)
    # Normalisation: statistics of the shown pixels of (unaugmented) training images.
    acc = []
    for i in rng.choice(len(train), size=min(200, len(train)), replace=False):
        img, _, mask = project(*train[i][:2], *FOV[train[i][2]])
        acc.append(img[:, mask])
    acc = np.concatenate(acc, axis=1)
    means, stds = acc.mean(1).astype(np.float32), acc.std(1).astype(np.float32)
    # Class weights: inverse square root of the pixel frequency (rare poles and trunks count).
    counts = np.bincount(np.concatenate([c for _, c, _, _ in train]), minlength=len(CLASSES)).astype(np.float64)
    weights = 1.0 / np.sqrt(np.maximum(counts, 1) / counts.sum())
    weights[0] = 0.0
    weights /= weights[1:][counts[1:] > 0].mean()
    weights[3] *= args.pole_weight
    print("pixel counts", dict(zip([c[0] for c in CLASSES], counts.astype(int))), flush=True)
    print("class weights", dict(zip([c[0] for c in CLASSES], np.round(weights, 3))), flush=True)

    net = RangeNet(4, len(CLASSES))
    params = sum(p.numel() for p in net.parameters())
    print(f"{params} parameters", flush=True)
    opt = torch.optim.AdamW(net.parameters(), lr=2e-3, weight_decay=1e-4)
    wt = torch.tensor(weights, dtype=torch.float32)
    budget = args.minutes * 60
    t0 = time.time()
    step = 0
    while time.time() - t0 < budget:
        frac = (time.time() - t0) / budget
        for g in opt.param_groups:
            g["lr"] = 2e-3 * 0.5 * (1 + math.cos(math.pi * frac))
        xs, ys = [], []
        for _ in range(args.batch):
            img, lab, mask = sample(train, rng, realism=args.realism, rare_crop=args.rare_crop)
            xs.append(normalise(img, mask, means, stds))
            ys.append(np.where(mask, lab, 0))
        x, y = torch.from_numpy(np.stack(xs)), torch.from_numpy(np.stack(ys))
        loss = F.cross_entropy(net(x), y, weight=wt, ignore_index=0)
        opt.zero_grad()
        loss.backward()
        opt.step()
        step += 1
        if step % 50 == 0:
            print(f"step {step} {time.time() - t0:.0f} s loss {loss.item():.3f}", flush=True)
    print(f"trained {step} steps of {args.batch} crops in {time.time() - t0:.0f} s", flush=True)
    ious = evaluate(net, heldout, means, stds)
    print("held-out pixel IoU:", {k: round(v, 3) for k, v in ious.items()}, flush=True)

    os.makedirs(args.out, exist_ok=True)
    torch.save({"state": net.state_dict(), "means": means, "stds": stds, "steps": step},
               os.path.join(args.out, "slide_range_net.pt.tmp"))  # for re-export; not committed
    net.eval()
    onnx_path = os.path.join(args.out, "slide_range_net.onnx")
    torch.onnx.export(net, torch.zeros(1, 4, HEIGHT, WIDTH), onnx_path, opset_version=11,
                      input_names=["range_image"], output_names=["logits"])
    with open(os.path.join(args.out, "slide_range_net.yaml"), "w") as f:
        f.write("# The project's range-image segmentation model (tools/train_range_net/train.py; how it was made and its\n")
        f.write(f"# held-out figures: README.md beside this file). {params} parameters, trained {step} steps of {args.batch} crops 64 x {CROP}, seed {args.seed},\n")
        f.write(f"# pole weight x{args.pole_weight}, realism {args.realism}, rare crops {args.rare_crop}, extra data {' '.join(args.extra) or '-'}.\n")
        f.write("model: slide_range_net.onnx\n")
        f.write(f"projection: {{height: {HEIGHT}, width: {WIDTH}, fov_up_deg: 3.0, fov_down_deg: -25.0}}  # HDL-64E; trained on OS1-64 (16.6 / -16.6) too\n")
        f.write("channels: [range, x, y, z]\n")
        f.write("means: [" + ", ".join(f"{m:.5f}" for m in means) + "]\n")
        f.write("stds: [" + ", ".join(f"{s:.5f}" for s in stds) + "]\n")
        f.write("scores: logits\n")
        f.write("classes:  # output channels in order: the model's class and the SemanticKITTI label its points get\n")
        for name, label, _ in CLASSES:
            f.write(f"  - {{name: {name}, label: {label}}}\n")
    print(f"wrote {onnx_path} ({os.path.getsize(onnx_path)} bytes)", flush=True)


if __name__ == "__main__":
    sys.exit(main())
