"""Run by pvbatch (scripts/render): rotating-drum or vibrated-sawtooth, the big grains alone (the drum from the side, the sawtooth's layer from above), big red, small yellow; orthographic and flat-shaded.
usage: pvbatch big_grains.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _granular import draw  # noqa: E402

draw("big")
