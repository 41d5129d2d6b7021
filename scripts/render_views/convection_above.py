"""Run by pvbatch (scripts/render): rayleigh-benard's convection as stream lines coloured by
temperature (see _convection.py), seen from above.
usage: pvbatch convection_above.py RUN_DIR OUT_PREFIX all|last WIDTH HEIGHT"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _convection import draw  # noqa: E402

draw("above")
