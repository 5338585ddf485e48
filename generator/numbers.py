"""Spec numbers (min, max, example values) as text and as fixed point, the way every runtime holds them."""

from __future__ import annotations

from decimal import Decimal


def fixed_point(value: object) -> tuple[int, int]:
    """A spec number (int, float or its text) as (digits, scale), signed, with
    digits * 10^-scale == value and no negative scale: 1.50 -> (15, 1), -2 -> (-2, 0), 1E+2 -> (100, 0)."""
    number = Decimal(fmt_num(value) if isinstance(value, float) else str(value))
    sign, digits, exponent = number.as_tuple()
    assert isinstance(exponent, int)
    magnitude = int("".join(map(str, digits)) or "0")
    if exponent > 0:
        magnitude *= 10 ** exponent
        exponent = 0
    return (-magnitude if sign else magnitude), -exponent


def fmt_num(value: float) -> str:
    return str(int(value)) if float(value).is_integer() else str(value)
