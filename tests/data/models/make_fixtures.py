#!/usr/bin/python3
"""Writes the small ONNX fixtures of tests/frontend (Debian's python3-onnx).

Run by hand when a fixture changes: /usr/bin/python3 tests/data/models/make_fixtures.py
The files are committed; the build does not run this script.

range3.onnx: input [1, 2, 4, 8] (range, z normalised), output [1, 3, 4, 8] from a 1x1
  convolution with known weights: class 0 scores 0.5, class 1 scores +range, class 2 -range.
  So a pixel is class 1 when its normalised range exceeds 0.5, class 2 below -0.5, else 0.
range2.onnx: the same input, only 2 output classes (a wrongly shaped model for a 3-class config).
yolo_seg.onnx: a YOLOv8-seg-shaped model, input [1, 3, 32, 32], outputs output0 [1, 38, 16]
  (2 classes) and output1 [1, 32, 8, 8] that do not depend on the image (zero-weight
  convolutions, known biases): every anchor is the box (cx 16, cy 12, w 16, h 8) of class 1
  with score 0.9, mask coefficient 0 = 1, prototype 0 = 2 everywhere (mask inside the box).
yolo_seg_37.onnx: the same with output0 [1, 37, 16] (a wrongly shaped model for 2 classes).
semantic.onnx: a per-pixel semantic model (test_semantic_seg.cpp), input [1, 3, 8, 16] (RGB in
  0..1), output logits [1, 3, 4, 8] at half the input size: a 2 x 2 average pool, then a 1x1
  convolution with known weights: class 0 scores 0.5, class 1 2 * red, class 2 2 * blue. So a
  red pixel is class 1 with softmax probability e^2 / (e^0.5 + e^2 + 1) = 0.736, a blue one
  class 2, a black one class 0 with 0.452.
semantic_2.onnx: the same with only classes 0 and 1 (a wrongly shaped model for 3 classes).
"""
import os

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

HERE = os.path.dirname(os.path.abspath(__file__))


def save(graph, name):
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)], producer_name="slide-fixture")
    onnx.checker.check_model(model)
    onnx.save(model, os.path.join(HERE, name))


def scores_1x1(classes, channels, weights):
    """Initialisers w, b of a 1x1 convolution to `classes` scores: class 0 scores 0.5, class k
    weights[(k, channel)] times the channel (the entries of classes present)."""
    w = np.zeros((classes, channels, 1, 1), dtype=np.float32)
    b = np.zeros(classes, dtype=np.float32)
    b[0] = 0.5
    for (k, channel), v in weights.items():
        if k < classes:
            w[k, channel] = v
    return [numpy_helper.from_array(w, "w"), numpy_helper.from_array(b, "b")]


def make_range(classes, name):
    conv = helper.make_node("Conv", ["range_image", "w", "b"], ["logits"], kernel_shape=[1, 1])
    save(helper.make_graph(
        [conv], "range_fixture",
        [helper.make_tensor_value_info("range_image", TensorProto.FLOAT, [1, 2, 4, 8])],
        [helper.make_tensor_value_info("logits", TensorProto.FLOAT, [1, classes, 4, 8])],
        scores_1x1(classes, 2, {(1, 0): 1.0, (2, 0): -1.0})), name)


def make_yolo(rows, name):
    bias0 = np.zeros(rows, dtype=np.float32)
    bias0[:4] = [16, 12, 16, 8]
    bias0[4:6] = [0.1, 0.9]
    if rows >= 38:
        bias0[6] = 1.0
    bias1 = np.zeros(32, dtype=np.float32)
    bias1[0] = 2.0
    inits = [numpy_helper.from_array(np.zeros((rows, 3, 1, 1), np.float32), "w0"), numpy_helper.from_array(bias0, "b0"),
             numpy_helper.from_array(np.zeros((32, 3, 1, 1), np.float32), "w1"), numpy_helper.from_array(bias1, "b1"),
             numpy_helper.from_array(np.array([1, rows, 16], np.int64), "shape0")]
    nodes = [helper.make_node("MaxPool", ["images"], ["pool8"], kernel_shape=[8, 8], strides=[8, 8]),
             helper.make_node("Conv", ["pool8", "w0", "b0"], ["grid0"], kernel_shape=[1, 1]),
             helper.make_node("Reshape", ["grid0", "shape0"], ["output0"]),
             helper.make_node("MaxPool", ["images"], ["pool4"], kernel_shape=[4, 4], strides=[4, 4]),
             helper.make_node("Conv", ["pool4", "w1", "b1"], ["output1"], kernel_shape=[1, 1])]
    graph = helper.make_graph(
        nodes, "yolo_seg_fixture", [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, 32, 32])],
        [helper.make_tensor_value_info("output0", TensorProto.FLOAT, [1, rows, 16]),
         helper.make_tensor_value_info("output1", TensorProto.FLOAT, [1, 32, 8, 8])], inits)
    save(graph, name)


def make_semantic(classes, name):
    nodes = [helper.make_node("AveragePool", ["image"], ["pool2"], kernel_shape=[2, 2], strides=[2, 2]),
             helper.make_node("Conv", ["pool2", "w", "b"], ["scores"], kernel_shape=[1, 1])]
    save(helper.make_graph(
        nodes, "semantic_fixture", [helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, 3, 8, 16])],
        [helper.make_tensor_value_info("scores", TensorProto.FLOAT, [1, classes, 4, 8])],
        scores_1x1(classes, 3, {(1, 0): 2.0, (2, 2): 2.0})), name)


if __name__ == "__main__":
    make_yolo(38, "yolo_seg.onnx")
    make_yolo(37, "yolo_seg_37.onnx")
    make_range(3, "range3.onnx")
    make_range(2, "range2.onnx")
    make_semantic(3, "semantic.onnx")
    make_semantic(2, "semantic_2.onnx")
    with open(os.path.join(HERE, "corrupt.onnx"), "wb") as f:
        f.write(b"this is not a protobuf model\n" * 4)
