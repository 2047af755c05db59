"""Regenerate the section "The e_n dip with the impact angle" of validation/report.md and its figures
(validation/figures/plastic_en_dip.png, plastic_dip_f.png): PE impacts at V_n = 2 and 5 m/s, 0-85 deg every
degree, Thornton's law uncoupled and with traction_yield="proportional" / "partial_slip".

Usage: python validation/plastic_dip.py [OUTDIR]   (default: the directory of this script)
"""
import os
import sys

from dem_contact.studies.plastic import update_dip_section

if __name__ == "__main__":
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    print(f"report updated: {update_dip_section(outdir)}")
