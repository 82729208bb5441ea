"""How numbers are written into the Markdown tables of results/: plain from 10⁻³ up to 10⁶ (a
timing of 12345 µs reads as 12345, not 1.234e+04), with `digits` significant digits but never an
integer part rounded to zeros; exponent notation only outside that range."""
import pytest

from pipeline.tables import PLAIN_RANGE, fmt, markdown_table


@pytest.mark.parametrize("value, text", [
    (12345.0, "12345"), (12345.6, "12346"), (-12345.6, "-12346"), (1e4, "10000"), (89640.37, "89640"),
    (999999.4, "999999"), (1234.56, "1235"), (9999.7, "10000"), (123.456, "123.5"), (0.5, "0.5"),
    (0.001, "0.001"), (0.0012345, "0.001234"), (5.0, "5")])
def test_plain_inside_the_range(value, text):
    assert fmt(value) == text


@pytest.mark.parametrize("value, text", [
    (1e6, "1.000e+06"), (2.7519e6, "2.752e+06"), (-7.442e22, "-7.442e+22"), (9.99e-4, "9.990e-04"),
    (6.597e-05, "6.597e-05"), (8.882e-16, "8.882e-16")])
def test_exponent_only_for_very_large_or_small_magnitudes(value, text):
    assert fmt(value) == text


def test_no_exponent_anywhere_in_the_plain_range_and_value_kept():
    """Every magnitude of the plain range, at every precision the reports ask for, in both signs:
    no exponent, and the text reads back within the requested significant digits."""
    lo, hi = PLAIN_RANGE
    for digits in (2, 3, 4):
        x = lo
        while x < hi:
            for value in (x, -x):
                text = fmt(value, digits)
                assert "e" not in text, (value, digits, text)
                assert float(text) == pytest.approx(value, rel=0.5 * 10 ** (1 - digits))
            x *= 1.0137


def test_other_values_and_a_table_row():
    assert [fmt(v) for v in (None, True, False, 123456789, 0.0, float("nan"))] == ["–", "yes", "no", "123456789",
                                                                                   "0", "nan"]
    assert markdown_table(["n", "t (µs)"], [[3, 23456.7]]).splitlines()[-1] == "| 3 | 23457 |"
