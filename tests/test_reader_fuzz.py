"""The reader never crashes with a traceback: it reads the file or explains why (issue 6)."""
import string

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from capred.errors import CapredError
from capred.pipelines.retention import run_retention
from capred.pipelines.shear import run_shear
from capred.pipelines.triaxial import run_triaxial_bounds

NAMES = ["test_id", "material", "condition", "z1", "z2", "V_v", "added_mass", "cap_mass", "box_area", "R",
         "tau_max", "sigma_N", "suction", "S_R", "Tau max", "tau_max_kPa", "Sr", "q_f", "sigma3", "head", "theta"]
UNITS = ["", " [kPa]", " (mm)", " [g]", " [cm^3]", " [%]", " [blorp]", " [kg/cm^2]", " [", " (]", " [m/s]"]
CELLS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-10**6, 10**6).map(str),
    st.sampled_from(["", "dry", "wet", "saturated", "unsaturated", "NA", "1,5", "0,35", "-", "nan", "1e309", '"x"']),
    st.text(alphabet=string.printable + "µ°é²", max_size=8),
)


@st.composite
def tables(draw):
    ncol = draw(st.integers(1, 8))
    header = [draw(st.sampled_from(NAMES)) + draw(st.sampled_from(UNITS)) for _ in range(ncol)]
    rows = draw(st.lists(st.lists(CELLS, min_size=0, max_size=ncol + 1), max_size=6))
    sep = draw(st.sampled_from([",", ";", "\t"]))
    quote = draw(st.booleans())

    def line(cells):
        return sep.join(f'"{c}"' if quote and sep not in c else c for c in cells)

    lines = [line(header)] + [line(r) for r in rows]
    if draw(st.booleans()):
        lines.insert(draw(st.integers(0, len(lines))), "# comment")
    if draw(st.booleans()):
        lines.insert(draw(st.integers(0, len(lines))), "")
    text = draw(st.sampled_from(["\n", "\r\n"])).join(lines)
    encoding = draw(st.sampled_from(["utf-8", "utf-8-sig", "cp1252", "utf-16"]))
    return text.encode(encoding, errors="replace")


SETTINGS = settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


@SETTINGS
@given(data=tables())
def test_fuzzed_tables_read_or_explain(tmp_path, data):
    path = tmp_path / "fuzz.csv"
    path.write_bytes(data)
    for run in (run_shear, run_triaxial_bounds, run_retention):
        try:
            run(path)
        except CapredError as exc:
            assert str(exc)  # a message, not a traceback


@SETTINGS
@given(data=st.binary(max_size=300))
def test_random_bytes_read_or_explain(tmp_path, data):
    path = tmp_path / "bytes.csv"
    path.write_bytes(data)
    try:
        run_shear(path)
    except CapredError:
        pass


def test_european_export_semicolon_decimal_comma_bom(tmp_path):
    text = ("\ufefftest_id;condition;sigma_N [kPa];tau_max [kPa]\r\n\r\n"
            "a;dry;1,0;1,0452\r\nb;dry;2,0;1,7598\r\n\"c\";dry;3,0;2,4744\r\n")
    path = tmp_path / "eu.csv"
    path.write_bytes(text.encode("utf-8"))
    js = run_shear(path).to_json()
    assert abs(js["materials"]["(all)"]["tan_phi"] - 0.7146) < 1e-9


NUM = st.one_of(st.floats(-1e3, 1e4, allow_nan=False).map(lambda x: f"{x:.6g}"), st.just(""), st.just("0"))


@st.composite
def valid_header_tables(draw, header, text_cols):
    rows = []
    for _ in range(draw(st.integers(1, 8))):
        rows.append(",".join(draw(st.sampled_from(text_cols[h])) if h in text_cols else draw(NUM) for h in header))
    return ",".join(header) + "\n" + "\n".join(rows) + "\n"


SHEAR_HEADER = ["test_id", "material", "condition", "z1", "z2", "V_v", "added_mass", "cap_mass", "box_area", "R", "tau_max"]
TRI_HEADER = ["test_id", "condition", "sigma3", "q_f", "p0", "s0", "sigma2", "group"]


@SETTINGS
@given(text=valid_header_tables(SHEAR_HEADER, {"test_id": ["a", "b", "c", "d", "e"], "material": ["m", "n"],
                                               "condition": ["dry", "wet"]}))
def test_fuzzed_values_shear(tmp_path, text):
    path = tmp_path / "v.csv"
    path.write_text(text)
    try:
        run_shear(path).to_json()
    except CapredError:
        pass


@SETTINGS
@given(text=valid_header_tables(TRI_HEADER, {"test_id": ["a", "b", "c", "d", "e"], "group": ["", "A"],
                                             "condition": ["saturated", "unsaturated"]}))
def test_fuzzed_values_triaxial(tmp_path, text):
    path = tmp_path / "v.csv"
    path.write_text(text)
    try:
        run_triaxial_bounds(path).to_json()
    except CapredError:
        pass
