"""A grammar of hostile strings for the property tests of the input boundary.

Each string is something a person might type (or paste) into an option or a query
field: numbers with huge and tiny exponents, 400-digit numbers, Unicode digits, empty
and blank text, NaN and infinities, commas and doubled separators, units, ``pi/0``,
control characters, and short combinations of these. Valid ordinary values are mixed
in so that the properties also cover inputs that run. Mantissas and exponents are
chosen so that a value that happens to be valid is never minutes of legitimate work.
"""
from hypothesis import strategies as st

EXTREME_EXPONENTS = [308, 309, 400, 401, 4000, 99999999, -307, -308, -320, -324, -400, -99999999]
ATOMS = [
    "", " ", "\t", "\n", "\u00a0", "\u2003", "0", "-0", "1", "-1", "2", "0.1", "1e-2", "7/2", ".5", "5.",
    "nan", "NaN", "inf", "-inf", "Infinity", "1e", "e5", "1e+", "--1", "+-1", "1e--2", "0x10", "1_000",
    "9" * 400, "0." + "0" * 398 + "1", "1" + "0" * 70,
    "１", "²", "١٢", "𝟏", "½", "Ⅻ", "٣.٥",
    ",", "1,2", "1,,2", "1,", ",1", "1, ,2", "1  2", "1::2", "1//2", "1:2:3", "1deg:2deg:0",
    "1m", "1cm", "1mm", "1ms", "1s", "1deg", "1°", "1rad", "1 furlong", "45 degrees east", "1e400deg",
    "pi", "pi/0", "4pi/5", "π/4", "-pi/4", "pi/1e-400", "1e400pi", "0/0", "1/0", "pi*pi",
    "taylor2", "taylor:0", "taylor:4", "taylor:99999999999", "rk4", "euler", "TAYLOR2",
    "none", "x.xyz", "x.png", "/no/such/dir/x.png", "\x00", "\x1b[31m", "a\nb", "'", '"', "%s", "{}",
]
MANTISSAS = ["1", "2.5", "0.5", "9.99", "12345", "-1", "1.0000000000000000000001"]


def _number(m: str, e: int) -> str:
    return f"{m}e{e}"


NUMBERS = st.builds(
    _number,
    st.sampled_from(MANTISSAS),
    st.one_of(st.sampled_from(EXTREME_EXPONENTS), st.integers(-3, 2), st.integers(-10**12, 10**12)),
)
ATOM = st.one_of(st.sampled_from(ATOMS), NUMBERS)
#: One hostile value: an atom, two or three atoms joined by a separator, or short random text.
HOSTILE = st.one_of(
    ATOM,
    st.builds(lambda parts, sep: sep.join(parts), st.lists(ATOM, min_size=2, max_size=3),
              st.sampled_from([",", " ", ", ", ",,", ":", "/", "", "deg", "pi"])),
    st.text(max_size=12),
)
