#!/usr/bin/env python3
"""Runs the tutorial of docs/decks.md: its Lua blocks, in order, form one deck, which
must run and reproduce the small-load cantilever reference (docs cannot drift)."""
import re
import subprocess
import sys
import tempfile

slender, doc = sys.argv[1], sys.argv[2]
text = open(doc).read()
tutorial = text[text.index("## Tutorial"):]
code = "\n".join(re.findall(r"```lua\n(.*?)```", tutorial, re.S))
with tempfile.NamedTemporaryFile("w", suffix=".lua", delete=False) as f:
    f.write(code)
out = subprocess.run([slender, f.name, "-q", "-v", "nodes=21"], capture_output=True, text=True)
print(out.stdout + out.stderr)
m = re.search(r"rel_error=([0-9.e+-]+)", out.stdout)
if out.returncode != 0 or not m or float(m.group(1)) > 2e-3:
    sys.exit("the tutorial deck failed or missed the reference")
print("tutorial: ok")
