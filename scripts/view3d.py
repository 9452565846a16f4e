"""The 3D helpers the picture scripts share (mesh_picture.py,
curved_picture.py): vectors as tuples, and the fixed orthographic view.
Standard library only."""

import math

VIEW = (0.35, -0.45, -0.82)  # from the camera towards the scene
PANEL = 420  # pixels per panel


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(dot(a, a)) or 1.0
    return (a[0] / n, a[1] / n, a[2] / n)
