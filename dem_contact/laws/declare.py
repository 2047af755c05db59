"""What a law declares about its inputs: the Scene settings it takes (``Option``) and the slots of the parameter
row it reads (``Param``). ``laws.table`` collects them: ``laws.generate`` numbers the parameter row from the
``Param`` declarations (``laws.slots``), and ``Scene``, the presets and the command line take their law
settings from the ``Option`` declarations.

Both are strings (an option's keyword name, a parameter's symbol), so that a law's ``OPTIONS`` and
``PARAMETERS`` read as names where only names matter.
"""
from __future__ import annotations

from ..errors import InputError
from ..materials import check_finite


class Option(str):
    """A Scene setting a law takes: its keyword name (the string), what it is (``doc``), its unit, its default,
    and how a value is checked: ``choices`` (the values accepted; a dict maps each to what it stands for),
    a numeric range (``lo``, ``hi``, ``lo_open``, ``hi_open``: ``materials.check_finite``), or ``parse`` (a
    function of the value that returns the checked value or raises InputError). None stands for "not given"
    when it is the default. ``per_law``: a value for one law is no value for another (a cell count), so
    ``Scene.with_tangential`` drops it when the law changes; ``short``: what it is in a few words, for
    messages (default ``doc``). ``cli``: the command line's argparse keyword
    arguments (e.g. ``nargs``), None: no command-line option (a setting the commands give themselves).
    Laws that take the same setting list the same Option."""

    def __new__(cls, name, doc, unit="", default=None, *, choices=None, lo=None, hi=None, lo_open=True,
                hi_open=False, parse=None, per_law=False, cli=None, short=None):
        self = super().__new__(cls, name)
        self.name, self.doc, self.unit, self.default = name, doc, unit, default
        self.choices = None if choices is None else tuple(choices)
        self.lo, self.hi, self.lo_open, self.hi_open = lo, hi, lo_open, hi_open
        self.parse, self.per_law, self.cli, self.short = parse, per_law, cli, short or doc
        return self

    def __reduce__(self):
        return str, (str(self),)

    @property
    def label(self) -> str:
        """The name with what it is (``short``) and its unit, for messages: ``v_ref (reference normal speed, m/s)``."""
        return f"{self.name} ({self.short}{', ' + self.unit if self.unit else ''})"

    @property
    def flag(self) -> str:
        """The command-line flag: ``--e-n``."""
        return "--" + self.name.replace("_", "-")

    def check(self, value):
        """The checked value of this setting (InputError naming it and the valid values)."""
        if value is None and self.default is None:
            return None
        if self.parse is not None:
            return self.parse(value)
        if self.choices is not None:
            if not isinstance(value, str) or value not in self.choices:
                raise InputError(f"{self.name} = {value!r} is unknown; choose one of: {', '.join(self.choices)}")
            return value
        if self.lo is None and self.hi is None:
            return value
        return check_finite(self.label, value, lo=self.lo, hi=self.hi, lo_open=self.lo_open, hi_open=self.hi_open)

    def describe(self) -> str:
        """One line for help texts and the Scene docstring."""
        rng = ""
        if self.choices is not None:
            rng = f"; one of {', '.join(self.choices)}"
        elif self.lo is not None or self.hi is not None:
            lo = "-inf" if self.lo is None else f"{self.lo:g}"
            hi = "inf" if self.hi is None else f"{self.hi:g}"
            rng = f"; {'(' if self.lo_open else '['}{lo}, {hi}{')' if self.hi_open or self.hi is None else ']'}"
        unit = f" [{self.unit}]" if self.unit else ""
        return f"{self.doc}{unit}{rng}"


class Param(str):
    """A slot of the parameter row that a law reads: its symbol (the string), its slot name in ``laws.slots``
    (``slot``), what it is, its unit, and ``size`` (consecutive slots: a table). Laws that read the same
    slot list a Param of the same slot name; the first law that lists it (``laws.table`` order) says what it
    is."""

    def __new__(cls, symbol, slot, doc, unit="", size=1):
        self = super().__new__(cls, symbol)
        self.symbol, self.slot, self.doc, self.unit, self.size = symbol, slot, doc, unit, int(size)
        return self

    def __reduce__(self):
        return str, (str(self),)


# the slots every row has, set by Scene from the pair of bodies and the laws it names
ESTAR = Param("E_star", "P_ESTAR", "effective Young's modulus E*", "Pa")
GSTAR = Param("G_star", "P_GSTAR", "effective shear modulus G*", "Pa")
RSTAR = Param("R_star", "P_RSTAR", "effective radius R*", "m")
MSTAR = Param("m_star", "P_MSTAR", "effective mass m*", "kg")
MU = Param("mu", "P_MU", "friction coefficient mu", "-")
NORMAL_LAW = Param("normal law", "P_NORMAL_LAW", "normal law id + 1 the row was built for (0: not recorded); no "
                   "kernel reads it, the checked entries refuse a row used with other law ids")
TANGENTIAL_LAW = Param("tangential law", "P_TANGENTIAL_LAW", "tangential law id + 1 the row was built for (0: not "
                       "recorded)")
TWIST_LAW = Param("twist law", "P_TWIST_LAW", "twist law id + 1 the row was built for (0: not recorded; the 3D "
                  "kernels read it)")
ROLLING_LAW = Param("rolling law", "P_ROLLING_LAW", "rolling law id + 1 the row was built for (0: not recorded; "
                    "the 3D kernels read it)")
COMMON = (ESTAR, GSTAR, RSTAR, MSTAR, MU, NORMAL_LAW, TANGENTIAL_LAW, TWIST_LAW, ROLLING_LAW)

#: the settings several laws take
E_N = Option("e_n", "target normal restitution: sets a dashpot, or calibrates a yield pressure at v_ref", "", None,
             lo=0.0, hi=1.0, lo_open=False, cli={}, short="normal restitution")
V_REF = Option("v_ref", "reference normal speed: the speed a stiffness is matched at, a yield pressure calibrated at, "
               "or (mdr) the largest normal speed expected, which sets the extent of the springs", "m/s", None, lo=0.0,
               short="reference normal speed")


def positive(name, doc, unit, **kw) -> Option:
    """A coefficient > 0 with no default (required by the law that takes it)."""
    return Option(name, doc, unit, None, lo=0.0, cli={}, **kw)


def non_negative(name, doc, unit, **kw) -> Option:
    """A coefficient >= 0 with no default (required by the law that takes it)."""
    return Option(name, doc, unit, None, lo=0.0, lo_open=False, cli={}, **kw)

