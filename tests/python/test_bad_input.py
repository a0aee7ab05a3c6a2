"""Bad spectrum files get a clear error naming file and line, and a non-zero exit."""

import pytest

from conftest import run_brume

GOOD_HEAD = "# a comment\nwavelength_nm,reflectance\n400,0.1\n500,0.2\n"


@pytest.mark.parametrize(
    "body,line,words",
    [
        (GOOD_HEAD + "450,0.3\n", 5, "strictly increasing"),
        (GOOD_HEAD + "600,-0.3\n", 5, "negative"),
        (GOOD_HEAD + "600,nan\n", 5, "not finite"),
        (GOOD_HEAD + "600,abc\n", 5, "not a number"),
        (GOOD_HEAD + "600,0.1,0.2\n", 5, "expected 2 fields"),
        ("lambda,r\n400,0.1\n", 1, "wavelength_nm"),
    ],
)
def test_bad_file_names_file_and_line(brume, tmp_path, body, line, words):
    f = tmp_path / "bad.csv"
    f.write_text(body)
    r = run_brume("spectrum", f, "--illuminant", "D65", check=False)
    assert r.returncode != 0
    assert f"{f}:{line}:" in r.stderr, r.stderr
    assert words in r.stderr, r.stderr


def test_unknown_name_lists_builtins(brume):
    r = run_brume("spectrum", "D66", check=False)
    assert r.returncode != 0 and "D65" in r.stderr


def test_good_file_works(brume, tmp_path):
    f = tmp_path / "good.csv"
    f.write_text(GOOD_HEAD + "700,0.5\n")
    assert run_brume("spectrum", f, "--illuminant", "A").returncode == 0
