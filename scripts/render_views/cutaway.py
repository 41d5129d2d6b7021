"""Run by pvbatch (scripts/render): rotating-drum or vibrated-sawtooth, the near half cut away to show the interior (the drum's x > 0, the front half of the sawtooth's container), big grains red, small yellow; orthographic and flat-shaded.
usage: pvbatch cutaway.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _granular import draw  # noqa: E402

draw("cutaway")
