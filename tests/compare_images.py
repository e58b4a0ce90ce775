"""Compares two PNG images of the same size: exit 0 when at most SHARE of the pixels differ
by more than TOLERANCE (0..255, any colour channel), else 1. Prints the figures.
Usage: compare_images.py A.png B.png TOLERANCE SHARE"""
import sys

import numpy as np
from PIL import Image

a = np.asarray(Image.open(sys.argv[1]).convert("RGB")).astype(int)
b = np.asarray(Image.open(sys.argv[2]).convert("RGB")).astype(int)
if a.shape != b.shape:
    print(f"sizes differ: {a.shape} and {b.shape}")
    sys.exit(1)
diff = np.abs(a - b).max(axis=2)
tolerance, share = int(sys.argv[3]), float(sys.argv[4])
over = float((diff > tolerance).mean())
print(f"max channel difference {diff.max()}, pixels differing {float((diff > 0).mean()):.5f}, over {tolerance}: {over:.5f} (allowed {share})")
sys.exit(0 if over <= share else 1)
