"""The example script of docs/python.md runs as written."""
import os
import re
import subprocess
import sys

from conftest import SOURCE


def test_the_documented_example_runs():
    with open(os.path.join(SOURCE, "docs", "python.md")) as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    assert len(blocks) == 1
    run = subprocess.run([sys.executable, "-c", blocks[0]], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    assert "Monte Carlo R =" in run.stdout and "pbd" in run.stdout
