"""Run by pvbatch (scripts/render): rotating-drum's middle cross-section, the grains within 1.5
of it seen along the axis inside the wall's circle, big grains red, small yellow: where radial
segregation shows its core of small grains.
usage: pvbatch section.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _granular import draw  # noqa: E402

draw("section")
