"""Regenerate validation/report.md and validation/figures/: the published cases of Wu, Thornton & Li (2009).

Usage: python validation/validate.py [OUTDIR]   (default: the directory of this script)
"""
import os
import sys

from dem_contact.studies.wu2009 import run_validation

if __name__ == "__main__":
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    print(f"report written to {run_validation(outdir)}")
