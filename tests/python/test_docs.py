"""docs/python.md's python blocks run in order, as one script, from the project folder."""

import re
import subprocess
import sys

from conftest import PROJECT


def test_the_python_page_runs(graspit_data):
    page = (PROJECT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", page, flags=re.S)
    assert len(blocks) >= 5
    script = "\n".join(blocks)
    done = subprocess.run([sys.executable, "-c", script], cwd=PROJECT, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert "settled [0.       1.024375 1.024375 1.121875]" in done.stdout
