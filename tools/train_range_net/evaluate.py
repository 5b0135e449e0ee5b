#!/usr/bin/python3
"""Held-out pixel IoU of an exported model (its .yaml and .onnx) through OpenCV DNN, with the
projection and scoring of train.py, so that two models are compared on the same scans.

Usage: /usr/bin/python3 tools/train_range_net/evaluate.py MODEL.yaml HELDOUT_DIR [--limit 8]
Needs Debian's python3-opencv; one thread.
"""
import argparse
import os
import re
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from train import CLASSES, FOV, iou_table, load_set, normalise, project  # noqa: E402


def read_vector(text, key):
    m = re.search(rf"^{key}:\s*\[([^\]]*)\]", text, re.M)
    return np.array([float(v) for v in m.group(1).split(",")], dtype=np.float32)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("model_yaml")
    ap.add_argument("heldout")
    ap.add_argument("--limit", type=int, default=8, help="held-out scans per run and robot")
    args = ap.parse_args()
    cv2.setNumThreads(1)
    text = open(args.model_yaml).read()
    means, stds = read_vector(text, "means"), read_vector(text, "stds")
    onnx = re.search(r"^model:\s*(\S+)", text, re.M).group(1)
    net = cv2.dnn.readNetFromONNX(os.path.join(os.path.dirname(args.model_yaml), onnx))
    data = load_set(args.heldout, limit=args.limit)
    conf = np.zeros((len(CLASSES), len(CLASSES)), dtype=np.int64)
    for pts, cls, sensor, _ in data:
        img, lab, mask = project(pts, cls, *FOV[sensor])
        net.setInput(normalise(img, mask, means, stds)[None])
        pred = net.forward()[0].argmax(0)
        t, p = lab[mask & (lab > 0)], pred[mask & (lab > 0)]
        np.add.at(conf, (t, p), 1)
    print(f"{args.model_yaml}: {len(data)} held-out scans, pixel IoU:",
          {k: round(v, 3) for k, v in iou_table(conf).items()}, flush=True)


if __name__ == "__main__":
    sys.exit(main())
