"""Constants that options take as defaults, declared once (the numerical modules import them from here).

Numpy-free (see :mod:`capred.spec`).

References
----------
.. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the capillary effective stress in granular
   materials. Master thesis, Vrije Universiteit Brussel (no DOI): sections "Apply suction", "Shear strength".
"""

#: Unit weight of water [N/m^3] used by default; the thesis uses 10 kN/m^3 [1].
GAMMA_W = 9810.0
#: Surface tension of water at 20 C [N/m].
SURFACE_TENSION = 0.0728
#: Gravitational acceleration [m/s^2].
G = 9.81
#: Upper S_R of the pendular regime used in the thesis [1] ("S_R < 5 %").
PENDULAR_LIMIT = 0.05

#: error models of `capred.fitting.linear.fit_envelope` (``auto`` chooses one of the first two by
#: `capred.fitting.linear.choose_errors`; ``either`` is valid under both: every interval is at least as wide as
#: each model's)
ERROR_MODELS = ("either", "constant", "proportional", "auto")
#: losses of `capred.fitting.linear.fit_envelope`
LOSSES = ("ols", "huber", "tukey")

#: Columns of a `capred pt-volume` path file, with their default unit (what
#: capred.physics.pedrotti_tarantino.simulate_volume_path takes, in SI; the schema of capred.spec.pt_volume and
#: the physics read them from here).
PATH_COLUMNS: dict[str, tuple[str, str]] = {
    "sigma": ("kPa", "total (mean) stress σ, compression positive"),
    "u_w": ("kPa", "pore-water pressure u_w (gauge; negative under suction)"),
    "u_a": ("kPa", "pore-air pressure u_a (gauge; 0 when the air is atmospheric)"),
    "S_r": ("-", "degree of saturation S_r, in [0, 1]"),
}
