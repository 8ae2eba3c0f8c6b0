#!/usr/bin/env python3
"""Writes tube.obj: an open cylinder (no caps) of radius 50 mm and length 200 mm along +z,
48 vertices around and 24 quads along, each quad split into two triangles, normals outward.
Run from this folder: python3 make_tube.py"""
import math

R, L, N, M = 50.0, 200.0, 48, 24
lines = ["# open tube: radius 50 mm, length 200 mm, axis +z from z=0 (written by make_tube.py)"]
for j in range(M + 1):
    for i in range(N):
        t = 2.0 * math.pi * i / N
        lines.append("v %r %r %r" % (R * math.cos(t), R * math.sin(t), L * j / M))
idx = lambda i, j: j * N + (i % N) + 1
for j in range(M):
    for i in range(N):
        lines.append("f %d %d %d" % (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)))
        lines.append("f %d %d %d" % (idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)))
with open("tube.obj", "w") as f:
    f.write("\n".join(lines) + "\n")
