"""The README's figures point at what holds them: every test, bench script and devtool it names
exists, every bench/RESULTS.md section it cites is there, and every RESULTS section names the
command that made it."""

import pathlib
import re

REPO = pathlib.Path(__file__).resolve().parent.parent
README = (REPO / "README.md").read_text()
RESULTS = (REPO / "bench" / "RESULTS.md").read_text()
HEADINGS = [line[3:] for line in RESULTS.splitlines() if line.startswith("## ")]


def test_every_file_the_readme_names_exists():
    folders = "tests|bench|devtools|addon|core|node_groups|operators|ui"
    named = set(re.findall(rf"\b((?:{folders})/[a-z_0-9/]+\.py)", README))
    assert len(named) > 30
    missing = sorted(path for path in named if not (REPO / path).is_file())
    assert not missing, missing


def test_every_results_section_the_readme_cites_is_there():
    cited = {" ".join(title.split()) for title in re.findall(r'bench/RESULTS\.md`?,? "([^"]+)"', README)}
    assert len(cited) >= 8
    missing = sorted(title for title in cited if not any(h.startswith(title) for h in HEADINGS))
    assert not missing, missing


def test_every_results_section_names_its_command():
    for heading in HEADINGS:
        assert re.search(r"`[^`]*(bench|devtools)/[a-z_]+\.py[^`]*`", heading), heading
