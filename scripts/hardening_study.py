#!/usr/bin/env python3
"""How the morphology of a crumpling deck depends on the hardening slope K_h of the bending
law (docs/models.md §2.2: K_h is not given by the thesis; the decks take the [C] default
0.05 K_e): scripts/crumple_study.py with --variable hardening.

  /usr/bin/python3 scripts/hardening_study.py [--f 25] [--ratios 0.05 0.1 0.2 0.4 0.8] \
      [--seeds 1 2] [--max-phi 0.2 | --jam]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from crumple_study import ROOT, main, shape_measures  # noqa: E402,F401

if __name__ == "__main__":
    raise SystemExit(main(variable="hardening", label="K_h/K_e",
                          default_out=os.path.join(ROOT, "docs", "crumple2d", "hardening")))
