"""Solver names and Siconos ids.

Names are matched case-insensitively, with ``-``, ``_`` and spaces equivalent, and with or without
Siconos' prefixes ``SICONOS_FRICTION_3D_`` / ``FC3D_`` (and ``ONECONTACT_`` for local solvers): so
``"NSN-AC"``, ``"nsn_ac"`` and ``"SICONOS_FRICTION_3D_NSN_AC"`` all mean 504. An integer (or a
string of digits) is taken as a Siconos id and passed to the library as is.
"""

import numbers

from . import _native
from ._errors import ERR_INVALID_OPTION, ERR_UNSUPPORTED_SOLVER, Fc3dError


def _solver_tables():
    """SOLVERS and its aliases, from the library's own list of the solvers it accepts."""
    table, aliases = {}, {}
    for sid, constant, name in _native.solvers():
        table[_normalize(constant)] = sid
        aliases.setdefault(_normalize(name), sid)
    return table, aliases


#: NSGS's local (one-contact) solvers: name -> Siconos id. ``"HYBRID"`` (565) is the default.
LOCAL_SOLVERS = {
    "NSN": 550,
    "NSN_GP": 551,
    "PROJECTION_ON_CONE": 552,
    "PROJECTION_ON_CONE_WITH_LOCAL_ITERATION": 553,
    "PROJECTION_ON_CONE_WITH_REGULARIZATION": 554,
    "PROJECTION_ON_CONE_WITH_DIAGONALIZATION": 555,
    "PROJECTION_ON_CYLINDER": 557,
    "PROJECTION_ON_CONE_VELOCITY": 558,
    "NCP_GLOCKER_FB_NEWTON": 561,
    "QUARTIC": 562,
    "PROJECTION_ON_CYLINDER_WITH_LOCAL_ITERATION": 564,
    "NSN_GP_HYBRID": 565,
    "FP_VI_UPK": 570,
    "EBP": 571,
    "EAL": 572,
}

# Other spellings (normalized): the names of `fc3d bench` (core/src/local/registry.rs) and
# Siconos' (SICONOS_FRICTION_3D_ONECONTACT_<name>; the prefixes are stripped before lookup).
_LOCAL_ALIASES = {
    "NSN_AC": 550,
    "NSN_AC_GP": 551,
    "PROJ": 552,
    "SBP": 552,
    "FP_DS_ONE": 552,
    "PROJECTIONONCONE": 552,
    "PROJ_ITER": 553,
    "PROJECTIONONCONEWITHLOCALITERATION": 553,
    "PROJ_REG": 554,
    "PROJECTIONONCONEWITHREGULARIZATION": 554,
    "PROJ_DIAG": 555,
    "PROJECTIONONCONEWITHDIAGONALIZATION": 555,
    "CYL": 557,
    "SAL": 557,
    "PROJECTIONONCYLINDER": 557,
    "PROJ_VEL": 558,
    "PROJECTIONONCONE_VELOCITY": 558,
    "FB": 561,
    "NSN_FB": 561,
    "NCPGLOCKERFBNEWTON": 561,
    "CYL_ITER": 564,
    "PROJECTIONONCYLINDERWITHLOCALITERATION": 564,
    "HYBRID": 565,
}


def _normalize(name):
    """Upper case, ``-`` and spaces as ``_``, Siconos' prefixes removed."""
    key = name.strip().upper().replace("-", "_").replace(" ", "_")
    for prefix in ("SICONOS_FRICTION_3D_", "FRICTION_3D_", "FC3D_"):
        if key.startswith(prefix):
            key = key[len(prefix):]
            break
    if key.startswith("ONECONTACT_"):
        key = key[len("ONECONTACT_"):]
    return key


def _lookup(name, table, aliases, what, code):
    """The id of ``name`` in ``table`` or ``aliases``; an integer (or digits) as is."""
    if isinstance(name, bool):
        raise TypeError("%s must be a name or an integer id, not %r" % (what, name))
    if isinstance(name, numbers.Integral) or (isinstance(name, str) and name.strip().isdigit()):
        value = int(name)
        if not -(2 ** 31) <= value < 2 ** 31:
            raise Fc3dError("fc3d: %s id %d is outside the range of a C int" % (what, value), code)
        return value
    if not isinstance(name, str):
        raise TypeError("%s must be a name or an integer id, not %r" % (what, name))
    key = _normalize(name)
    if key in table:
        return table[key]
    if key in aliases:
        return aliases[key]
    known = ", ".join("%s (%d)" % (k, v) for k, v in table.items())
    raise Fc3dError(
        "fc3d: unknown %s '%s'; known: %s, or an integer id" % (what, name, known), code
    )


def solver_id(solver):
    """The Siconos id of ``solver``: a name of :data:`SOLVERS` or an alias, or an integer id.

    Raises Fc3dError (code ``ERR_UNSUPPORTED_SOLVER``) for an unknown name; an unknown integer id
    is rejected by the library when the settings are created.
    """
    return _lookup(solver, SOLVERS, _SOLVER_ALIASES, "solver", ERR_UNSUPPORTED_SOLVER)


def local_solver_id(local_solver):
    """The Siconos id of NSGS's local solver ``local_solver``: a name of :data:`LOCAL_SOLVERS`,
    an alias (``"HYBRID"``, ``"SBP"``, ``"SAL"``, ``"EBP"``, ...), or an integer id."""
    return _lookup(local_solver, LOCAL_SOLVERS, _LOCAL_ALIASES, "local solver", ERR_INVALID_OPTION)


#: Every solver of the native entry: short name -> Siconos id, as the library lists them at
#: import (``fc3d_solver_count`` / ``fc3d_solver_at``): the name of the solver's constant in the
#: C headers without its prefix (``SICONOS_FRICTION_3D_NSN_AC`` -> ``"NSN_AC"``, ``FC3D_AUTO`` ->
#: ``"AUTO"``). Siconos' name strings (``"FC3D_DeSaxceFixedPoint"``) are accepted too.
SOLVERS, _SOLVER_ALIASES = _solver_tables()


def solver_name(solver_id_):
    """The short name of a solver id (``"NSGS"`` for 500), or the id as a string."""
    for name, sid in SOLVERS.items():
        if sid == solver_id_:
            return name
    return str(solver_id_)
