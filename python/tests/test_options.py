"""The batch's options, described once: every option is in `encore batch --help`, in
Renderer.batch's docstring and in docs/batch.md's table; keywords are checked as the command
line checks them; an unknown keyword names the nearest one.

Run by CTest (python_module_tests) with PYTHONPATH pointing at the built module and
ENCORE_BINARY at the encore executable.
"""

import os
import pathlib
import subprocess

import pytest

import encore
from test_encore import generate, read_png

DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs" / "batch.md"


def encore_help(*arguments):
    return subprocess.run([os.environ["ENCORE_BINARY"], *arguments, "--help"], check=True,
                          capture_output=True, text=True).stdout


def test_every_option_is_in_the_help_the_docstring_and_the_docs():
    options = encore.batch_options()
    assert len(options) >= 45
    batch_help = encore_help("batch")
    program_help = encore_help()
    docstring = encore.Renderer.batch.__doc__
    docs = DOCS.read_text()
    table = docs[docs.index("## Options"):docs.index("## Input")]
    for option in options:
        keyword = option["keyword"]
        assert f"\n{keyword} (" in docstring, keyword
        assert f"`{keyword}" in table, keyword
        if option["command_line"]:
            name = option["command_line"]
            assert f"{name} " in batch_help or f",{name} " in batch_help or \
                f"{name} " in program_help, name
            assert f"{name}`" in table or f"{name} batch`" in table, name
        if option["default"] is not None and option["choices"]:
            assert option["default"] in option["choices"], keyword


def test_an_unknown_keyword_names_the_nearest_one(tmp_path):
    renderer = encore.Renderer()
    with pytest.raises(TypeError, match="did you mean 'views'"):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), viewz=3)
    with pytest.raises(TypeError, match="did you mean 'tone_mapping'"):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), tone_maping="aces")
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour_grading'"):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), colour_grading=1)
    with pytest.raises(TypeError, match="views takes an int"):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), views="3")
    with pytest.raises(ValueError, match="views takes a whole number from 1 to 10000"):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), views=0)
    with pytest.raises(ValueError, match="random_views and elevation exclude each other"):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), random_views=2,
                       elevation=10)
    assert not (tmp_path / "out").exists()


def test_keywords_of_the_command_line_reach_the_pictures(tmp_path):
    """Shading options that batch() had no keyword for before the shared description."""
    model = generate(tmp_path / "in" / "m.glb", objects=2)
    summary = encore.batch([(str(model), "m")], str(tmp_path / "out"), views=1, size=24,
                           samples=1, background="#ff0000", tone_mapping="none", exposure=1.0,
                           punctual_lights=False)
    assert summary["rendered"] == 1 and summary["failed"] == 0
    pixels = read_png(tmp_path / "out" / "m" / "000.png")
    assert tuple(pixels[0][0]) == (255, 0, 0, 255)  # The corner shows the background colour.
    # The same job on the command line writes the same file.
    subprocess.run([os.environ["ENCORE_BINARY"], "batch", str(model), "-o", str(tmp_path / "cli"),
                    "--views", "1", "--size", "24", "--samples", "1", "--background", "#ff0000",
                    "--tonemap", "none", "--exposure", "1", "--no-lights", "--quiet"], check=True)
    assert (tmp_path / "cli" / "m" / "000.png").read_bytes() == \
        (tmp_path / "out" / "m" / "000.png").read_bytes()
