"""One input column of a command's table, as its schema declares it (numpy-free: see :mod:`capred.spec`)."""

from __future__ import annotations

from dataclasses import dataclass

from ..nomenclature import column_aliases

#: numeric columns whose absence changes the analysis, so that a near miss of their name stops the run
#: (capred.io.table: a header one typo away from one of these is refused, not ignored)
DECISIVE_COLUMNS = frozenset({"R", "R2", "back_pressure", "u_a", "weight"})


@dataclass(frozen=True)
class Column:
    """One input column: canonical name, quantity kind, default unit and valid range.

    Attributes
    ----------
    name : str
        The canonical header.
    kind : str
        A key of ``capred.units.SI_UNIT``, or ``"text"``.
    unit : str or None
        The unit a bare number in the column is read in (``None`` for text).
    description : str
        What ``--help`` says about the column.
    aliases : tuple of str
        Other accepted spellings (the glossary's, ``capred.nomenclature.COLUMN_ALIASES``, are added).
    rule : str or None
        ``"positive"``, ``"nonnegative"``, ``"fraction"``, ``"coefficient"`` ((0, 1]) or None.
    choices : tuple of str
        The allowed values of a text column (lower case).
    quantity : str or None
        Its glossary entry: the entry's range rule is used (the same as for options).
    words : tuple of (str, float)
        Words a numeric column also accepts, e.g. ``("plane", inf)``.
    decisive : bool or None
        Whether its absence changes the analysis (None: text columns and `DECISIVE_COLUMNS`).
    """

    name: str
    kind: str  # a key of capred.units.SI_UNIT, or "text"
    unit: str | None
    description: str
    aliases: tuple[str, ...] = ()
    rule: str | None = None  # "positive", "nonnegative", "fraction", "coefficient" ((0, 1]), or None
    choices: tuple[str, ...] = ()  # allowed values of a text column (lower case)
    quantity: str | None = None  # nomenclature name: its range rule is used (the same as for options)
    words: tuple[tuple[str, float], ...] = ()  # words a numeric column also accepts, e.g. ("plane", inf)
    decisive: bool | None = None  # its absence changes the analysis (None: text columns and DECISIVE_COLUMNS)

    def __post_init__(self):
        # the glossary's spellings of this column (capred.nomenclature.COLUMN_ALIASES) come with every schema
        extra = tuple(a for a in column_aliases(self.name) if a not in self.aliases and a != self.name)
        if extra:
            object.__setattr__(self, "aliases", (*self.aliases, *extra))

    @property
    def is_decisive(self) -> bool:
        """True when a near miss of this column's name must stop the run (see capred.io.table)."""
        if self.decisive is not None:
            return self.decisive
        return self.kind == "text" or self.name in DECISIVE_COLUMNS
