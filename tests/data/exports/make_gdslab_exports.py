"""Write the GDSLAB-layout triaxial exports of this folder from the physics of the tests they record.

Run ``python make_gdslab_exports.py`` in this folder to rewrite them (tests/test_triaxial_exports_real_layout.py
checks that the files are what this script writes). Every number is computed here from a stated law; nothing
is measured. The layout (57 columns, their names, order and units, the quoted ``"Key:","Value"`` header
block) is that of a GDSLAB v2 triaxial data file; see SOURCES.md for where the column list comes from.
"""

from __future__ import annotations

import math
from pathlib import Path

HERE = Path(__file__).parent

#: the 57 columns of a GDSLAB triaxial data file with the unsaturated option, in the order GDSLAB writes them
COLUMNS = [
    "Stage Number",
    "Time since start of test (s)",
    "Time since start of stage (s)",
    "Radial Pressure (kPa)",
    "Radial Volume (mm³)",
    "Back Pressure (kPa)",
    "Back Volume (mm³)",
    "Load Cell (kN)",
    "Pore Pressure (kPa)",
    "Axial Displacement (mm)",
    "Axial Force (kN)",
    "Axial Strain (%)",
    "Av Diameter Change (mm)",
    "Radial Strain (%)",
    "Axial Stress (kPa)",
    "Eff. Axial Stress (kPa)",
    "Eff. Radial Stress (kPa)",
    "Deviator Stress (kPa)",
    "Total Stress Ratio",
    "Eff. Stress Ratio",
    "Shear Strain (%)",
    "Cambridge p (kPa)",
    "Eff. Cambridge p' (kPa)",
    "Max Shear Stress t (kPa)",
    "Volume Change (mm³)",
    "B Value",
    "Mean Stress s/Eff. Axial Stress 2",
    "Excess PWP (kPa)",
    "PWP Ratio",
    "L/C Pressure (kPa)",
    "L/C Volume (mm³)",
    "Local Axial 1 (mm)",
    "Local Axial 2 (mm)",
    "Local Radial (mm)",
    "Base Pressure (kPa)",
    "Base Volume (mm³)",
    "Back Differential Pressure (kPa)",
    "Axial Displacement 2 (mm)",
    "Pore Air Pressure (kPa)",
    "Pore Air Volume (mm³)",
    "Atmospheric Pressure (kPa)",
    "Temperature (°C)",
    "Mid Plane PWP (kPa)",
    "Back to Cell Differential (kPa)",
    "Total Volume Change (mm³)",
    "Undefined Tx 1",
    "Undefined Tx 2",
    "Undefined Tx 3",
    "Current Area (mm²)",
    "Lower Chamber Displacement (mm)",
    "Lower Chamber Axial Load (kN)",
    "Specimen Air Volume (mm³)",
    "Matric Suction (kPa)",
    "Voids ratio",
    "Degree of Saturation (%)",
    "Specimen Water Volume (mm³)",
    "kRT constant",
]
assert len(COLUMNS) == 57 and len(set(COLUMNS)) == 57

D0, H0 = 38.0, 76.0  # specimen [mm]
A0 = math.pi * D0**2 / 4  # [mm²]
V0 = A0 * H0  # [mm³]


def _reading(stage, t, ts, cell, back, u, eps, q, ua=0.0, e=0.60, sr=100.0, dv=0.0, b_value=0.0):
    """One row of all 57 columns from the state of the specimen (pressures [kPa], eps [%], q [kPa], dv [mm³])."""
    area = A0 * (1 - dv / V0) / (1 - eps / 100)  # right cylinder (ASTM D4767)
    force = q * area / 1e6  # [kN]
    s1, s3 = cell + q, cell
    u_ref = ua if ua else u  # net stress of an unsaturated test, effective of a saturated one
    e1, e3 = s1 - u_ref, s3 - u_ref
    p, pe = (s1 + 2 * s3) / 3, (e1 + 2 * e3) / 3
    vw = e * sr / 100 / (1 + e) * V0 * (1 - dv / V0)
    va = e * (1 - sr / 100) / (1 + e) * V0 * (1 - dv / V0)
    values = {
        "Stage Number": stage,
        "Time since start of test (s)": t,
        "Time since start of stage (s)": ts,
        "Radial Pressure (kPa)": cell,
        "Radial Volume (mm³)": 125000.0 - 2.1 * t / 60,
        "Back Pressure (kPa)": back,
        "Back Volume (mm³)": 98000.0 - dv,
        "Load Cell (kN)": force + 0.012,
        "Pore Pressure (kPa)": u,
        "Axial Displacement (mm)": eps / 100 * H0,
        "Axial Force (kN)": force,
        "Axial Strain (%)": eps,
        "Av Diameter Change (mm)": D0 * (math.sqrt((1 - dv / V0) / (1 - eps / 100)) - 1),
        "Radial Strain (%)": -100 * (math.sqrt((1 - dv / V0) / (1 - eps / 100)) - 1),
        "Axial Stress (kPa)": s1,
        "Eff. Axial Stress (kPa)": e1,
        "Eff. Radial Stress (kPa)": e3,
        "Deviator Stress (kPa)": q,
        "Total Stress Ratio": s1 / s3,
        "Eff. Stress Ratio": e1 / e3,
        "Shear Strain (%)": 2 / 3 * (eps - (dv / V0 * 100 - eps) / 2),  # 2/3 (eps_a - eps_r)
        "Cambridge p (kPa)": p,
        "Eff. Cambridge p' (kPa)": pe,
        "Max Shear Stress t (kPa)": q / 2,
        "Volume Change (mm³)": dv,
        "B Value": b_value,
        "Mean Stress s/Eff. Axial Stress 2": (e1 + e3) / 2,
        "Excess PWP (kPa)": u - back,
        "PWP Ratio": (u - back) / (cell - back) if cell != back else 0.0,
        "L/C Pressure (kPa)": 0.0,
        "L/C Volume (mm³)": 0.0,
        "Local Axial 1 (mm)": 0.0,
        "Local Axial 2 (mm)": 0.0,
        "Local Radial (mm)": 0.0,
        "Base Pressure (kPa)": u,
        "Base Volume (mm³)": 0.0,
        "Back Differential Pressure (kPa)": 0.0,
        "Axial Displacement 2 (mm)": 0.0,
        "Pore Air Pressure (kPa)": ua,
        "Pore Air Volume (mm³)": 0.0,
        "Atmospheric Pressure (kPa)": 101.3,
        "Temperature (°C)": 20.4,
        "Mid Plane PWP (kPa)": u,
        "Back to Cell Differential (kPa)": cell - back,
        "Total Volume Change (mm³)": dv,
        "Undefined Tx 1": 0.0,
        "Undefined Tx 2": 0.0,
        "Undefined Tx 3": 0.0,
        "Current Area (mm²)": area,
        "Lower Chamber Displacement (mm)": 0.0,
        "Lower Chamber Axial Load (kN)": 0.0,
        "Specimen Air Volume (mm³)": va,
        "Matric Suction (kPa)": ua - u if ua else 0.0,
        "Voids ratio": e,
        "Degree of Saturation (%)": sr,
        "Specimen Water Volume (mm³)": vw,
        "kRT constant": 0.0,
    }
    return [values[c] for c in COLUMNS]


def _text(v, decimal_comma: bool) -> str:
    s = str(v) if isinstance(v, int) else f"{v + 0.0:.4f}".replace("-0.0000", "0.0000")
    return s.replace(".", ",") if decimal_comma else s


def _write(path: Path, head: list[tuple[str, str]], rows: list[list], delimiter=",", decimal_comma=False):
    """The file as GDSLAB writes it: the quoted header block, the column names, the readings.

    With ``decimal_comma`` (a computer whose regional setting writes decimal commas) every '.' of the file
    becomes ',', the column names' included ("Eff, Axial Stress"), and the delimiter is ';'.
    """
    names = [c.replace(".", ",") for c in COLUMNS] if decimal_comma else COLUMNS

    def quote(x):
        return '"' + x.replace('"', '""') + '"'

    lines = [delimiter.join((quote(k + ":"), quote(v.replace(".", ",") if decimal_comma else v))) for k, v in head]
    lines.append(delimiter.join(quote(n) for n in names))
    lines += [delimiter.join(_text(v, decimal_comma) for v in r) for r in rows]
    path.write_text("\r\n".join(lines) + "\r\n", encoding="utf-8")


def _head(test: str, kind: str, **more) -> list[tuple[str, str]]:
    head = [
        ("Station Name", "Triax 2"),
        ("Test Name", test),
        ("Test Type", kind),
        ("Date Test Started", "14/03/2024 09:12:05"),
        ("Job Location", "capred test data (computed, not measured)"),
        ("Borehole", "BH-1"),
        ("Sample Name", test),
        ("Depth", "4.50 m"),
        ("Sample Date (dd/mm/yyyy)", "11/03/2024"),
        ("Description of Sample", "silty clay, reconstituted"),
        ("Initial Height (mm)", f"{H0:.1f}"),
        ("Initial Diameter (mm)", f"{D0:.1f}"),
        ("Specific Gravity (kN/m³)", "2.70"),
        ("Specimen Type (dis/undis)", "undis"),
        ("Top Drain Used (y/n)", "y"),
        ("Base Drain Used (y/n)", "y"),
        ("Side Drains Used (y/n)", "n"),
        ("Membrane Thickness (mm)", "0.20"),
    ]
    return head + list(more.items())


# --- CU test: saturation, B check, consolidation, undrained shear --------------------------------------------------
#: Skempton's B the B check measures, and A at failure (Skempton 1954): Δu = B (Δσ3 + A Δq)
CU_B, CU_A_F = 0.96, 0.55
CU_Q_PEAK, CU_EPS_PEAK = 97.3, 4.25  # [kPa], [%]
CU_CELL_DRIFT = 3.0  # the cell pressure creeps up by 3 kPa (0.75 %, within ASTM D4767's 1 %) over the shear stage [kPa]


def cu_rows() -> list[list]:
    """The four stages of a consolidated undrained test on a saturated specimen.

    1. Saturation ramp: cell 20 -> 310 kPa, back pressure 10 -> 300 kPa (10 kPa effective).
    2. B check: drainage closed, cell 310 -> 360 kPa; the pore pressure rises by B x 50 kPa.
    3. Isotropic consolidation: cell 400 kPa, back pressure 300 kPa (sigma'3 = 100 kPa); the excess pore
       pressure dissipates.
    4. Undrained shear to 15 % axial strain; q peaks at 97.3 kPa at 4.25 %; Δu = B (Δσ3 + A(ε) Δq) with A
       rising to 0.55 at the peak; the cell pressure creeps by 3 kPa.

    The B Value column is GDSLAB's running ratio Δu/Δσ3 from the first reading of each stage (0 on that
    reading): 0.96 at the end of the B check, and a number with no meaning in the shear stage, where Δσ3 is
    only the cell's creep.
    """
    rows, t = [], 0
    # 1. saturation ramp: 11 readings an hour apart
    for k in range(11):
        cell, back = 20.0 + 29 * k, 10.0 + 29 * k
        rows.append(_reading(1, t, 3600 * k, cell, back, back - 0.2 * (k > 0), 0.0, 0.35, b_value=1.0 if k else 0.0))
        t += 3600
    # 2. B check: the cell steps up 50 kPa; u approaches 300 + B 50 (time constant 90 s)
    u0 = rows[-1][COLUMNS.index("Pore Pressure (kPa)")]
    for k in range(8):
        cell = 310.0 if k == 0 else 360.0
        u = u0 if k == 0 else u0 + CU_B * 50 * (1 - math.exp(-120 * k / 90)) / (1 - math.exp(-120 * 7 / 90))
        rows.append(_reading(2, t, 120 * k, cell, 300.0, u, 0.0, 0.35, b_value=(u - u0) / (cell - 310.0) if k else 0.0))
        t += 120
    u_b = rows[-1][COLUMNS.index("Pore Pressure (kPa)")]
    # 3. consolidation: cell 400 kPa, drainage open to 300 kPa; u from u_b + B 40 down to 300.3 (one-dimensional
    # dissipation, taken exponential); water out of the specimen: 1.9 % of its volume
    for k in range(10):
        cell = 360.0 if k == 0 else 400.0
        u = u_b if k == 0 else 300.3 + (u_b + CU_B * 40 - 300.3) * math.exp(-(k - 1) / 1.5)
        dv = 0.019 * V0 * (1 - math.exp(-k / 1.5))
        b = (u - u_b) / (cell - 360.0) if k else 0.0
        rows.append(_reading(3, t, 9000 * k, cell, 300.0, u, 0.0, 0.35, e=0.60 - 1.6 * dv / V0, dv=dv, b_value=b))
        t += 9000
    dv_c = rows[-1][COLUMNS.index("Volume Change (mm³)")]
    e_c = rows[-1][COLUMNS.index("Voids ratio")]
    # 4. undrained shear, 0.25 % a reading, 0.05 %/min
    u_s, n = rows[-1][COLUMNS.index("Pore Pressure (kPa)")], 60
    q0 = 0.35
    for k in range(n + 1):
        eps = 0.25 * k
        x = eps / CU_EPS_PEAK
        q = q0 + (CU_Q_PEAK - q0) * (2 * x / (1 + x * x)) ** 0.6
        a = 0.30 + (CU_A_F - 0.30) * (1 - math.exp(-3 * x)) / (1 - math.exp(-3))
        ds3 = CU_CELL_DRIFT * k / n
        du = CU_B * (ds3 + a * (q - q0))
        b = du / ds3 if k else 0.0
        rows.append(_reading(4, t, 300 * k, 400.0 + ds3, 300.0, u_s + du, eps, q, e=e_c, dv=dv_c, b_value=b))
        t += 300
    return rows


def write_cu(path: Path, decimal_comma: bool = True) -> Path:
    """The CU export as a computer with decimal commas writes it (';' delimiter, "Eff, Axial Stress")."""
    _write(
        path,
        _head("CU-1", "Standard Triaxial (CU)"),
        cu_rows(),
        delimiter=";" if decimal_comma else ",",
        decimal_comma=decimal_comma,
    )
    return path


# --- unsaturated CD test under axis translation ---------------------------------------------------------------------
UNSAT_UA, UNSAT_UW, UNSAT_CELL = 300.0, 250.0, 400.0  # pore-air, pore-water (back) and cell pressure [kPa]
UNSAT_Q_PEAK, UNSAT_EPS_PEAK = 268.0, 6.0  # [kPa], [%]


def unsat_rows() -> list[list]:
    """Constant-suction drained shear of an unsaturated specimen (axis translation, u_a 300, u_w 250 kPa).

    Matric suction 50 kPa at the start of shear, drifting to 51.2 kPa at 12 % (the water pressure is held; the
    air pressure regulator creeps); void ratio 0.700 at the start, compressing to 0.684 at the peak and
    dilating after it; degree of saturation 62 % rising as the voids close (constant water volume:
    S_r e = const).
    """
    rows, t, n = [], 0, 48
    e0, sr0 = 0.700, 62.0
    for k in range(n + 1):
        eps = 0.25 * k
        x = eps / UNSAT_EPS_PEAK
        q = UNSAT_Q_PEAK * (2 * x / (1 + x * x)) ** 0.5
        e = e0 - 0.016 * (2 * x - x * x) if x <= 1 else e0 - 0.016 + 0.004 * (x - 1)
        sr = sr0 * e0 / e
        ua = UNSAT_UA + 1.2 * k / n
        dv = (e0 - e) / (1 + e0) * V0
        rows.append(_reading(1, t, 600 * k, UNSAT_CELL, UNSAT_UW, UNSAT_UW, eps, q, ua=ua, e=e, sr=sr, dv=dv))
        t += 600
    return rows


def write_unsat(path: Path) -> Path:
    """The unsaturated CD export (',' delimiter, decimal points, headers as GDSLAB names them)."""
    _write(path, _head("UD-50", "Unsaturated Triaxial (CD, axis translation)"), unsat_rows())
    return path


# --- three drained tests with back pressure; one cell pressure drifts 1.3 % -----------------------------------------
DRAINED_C, DRAINED_PHI = 5.0, 30.0  # the envelope the three tests follow [kPa], [deg]
DRAINED_SIGMA3 = {"D-100": 300.0, "D-200": 400.0, "D-300": 500.0}  # total cell pressure of the tests table [kPa]
DRAINED_BACK = 200.0  # [kPa]
DRAINED_DRIFT = {"D-200": 1.013}  # the logged cell pressure of D-200 is 1.3 % above the table's sigma3


def drained_peak(sigma3_eff: float) -> float:
    """q at failure on the envelope c', phi': sigma'1 = Kp sigma'3 + 2 c' sqrt(Kp) [kPa]."""
    kp = math.tan(math.radians(45 + DRAINED_PHI / 2)) ** 2
    return (kp - 1) * sigma3_eff + 2 * DRAINED_C * math.sqrt(kp)


def drained_rows(test: str) -> list[list]:
    """A drained shear stage: q = q_f (2x/(1+x^2))^0.5, x = eps/5 %; back pressure 200 kPa."""
    s3 = DRAINED_SIGMA3[test]
    qf = drained_peak(s3 - DRAINED_BACK)
    cell = s3 * DRAINED_DRIFT.get(test, 1.0)
    rows, t = [], 0
    for k in range(41):
        eps = 0.25 * k
        x = eps / 5.0
        q = qf * (2 * x / (1 + x * x)) ** 0.5
        rows.append(_reading(1, t, 600 * k, cell, DRAINED_BACK, DRAINED_BACK, eps, q, dv=-15.0 * k))
        t += 600
    return rows


def write_drained(folder: Path) -> list[Path]:
    """The three drained exports, one file per test."""
    folder.mkdir(exist_ok=True)
    out = []
    for test in DRAINED_SIGMA3:
        p = folder / f"{test}.csv"
        _write(p, _head(test, "Standard Triaxial (CD)"), drained_rows(test))
        out.append(p)
    return out


def write_all(folder: Path = HERE) -> list[Path]:
    """Every file of this folder that this script makes."""
    return [
        write_cu(folder / "gdslab_cu_decimal_comma.csv"),
        write_unsat(folder / "gdslab_unsaturated_cd.csv"),
        *write_drained(folder / "drained_drift"),
    ]


if __name__ == "__main__":
    for p in write_all():
        print(p)
