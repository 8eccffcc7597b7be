"""The exception of the package and the C library's return codes (``FC3D_*`` of fc3d_native.h)."""

# Return codes of the C entry (capi/include/fc3d_native.h).
OK = 0
NOT_CONVERGED = 1
TIME_BUDGET_EXHAUSTED = 2
RELAXED_NOT_COULOMB = 3
ERR_NULL_POINTER = -1
ERR_INVALID_SIZE = -2
ERR_INVALID_STORAGE = -3
ERR_NON_FINITE = -4
ERR_INVALID_OPTION = -5
ERR_UNSUPPORTED_SOLVER = -6
ERR_INVALID_PROBLEM = -7
ERR_PARSE = -8
ERR_IO = -9
ERR_INTERNAL = -99

#: Name of every error code, as in the C header (``FC3D_ERR_*``).
ERROR_NAMES = {
    ERR_NULL_POINTER: "FC3D_ERR_NULL_POINTER",
    ERR_INVALID_SIZE: "FC3D_ERR_INVALID_SIZE",
    ERR_INVALID_STORAGE: "FC3D_ERR_INVALID_STORAGE",
    ERR_NON_FINITE: "FC3D_ERR_NON_FINITE",
    ERR_INVALID_OPTION: "FC3D_ERR_INVALID_OPTION",
    ERR_UNSUPPORTED_SOLVER: "FC3D_ERR_UNSUPPORTED_SOLVER",
    ERR_INVALID_PROBLEM: "FC3D_ERR_INVALID_PROBLEM",
    ERR_PARSE: "FC3D_ERR_PARSE",
    ERR_IO: "FC3D_ERR_IO",
    ERR_INTERNAL: "FC3D_ERR_INTERNAL",
}

#: Meaning of the non-negative ``info`` a solve returns.
STATUS_NAMES = {
    OK: "converged",
    NOT_CONVERGED: "max_iter",
    TIME_BUDGET_EXHAUSTED: "time_budget",
    RELAXED_NOT_COULOMB: "relaxed_not_coulomb",
}


class Fc3dError(Exception):
    """An input fc3d rejected, or a failure of the C library.

    Attributes:
        code: the library's negative error code (``fc3d.ERR_*``, e.g. ``fc3d.ERR_NON_FINITE``
            = -4 for a NaN in q, ``fc3d.ERR_INVALID_PROBLEM`` = -7 for a negative mu).
        message: the library's message (``fc3d_last_error_message()``), or for checks only
            Python can make (array lengths, solver names) a message in the same style.

    ``str(error)`` is the message; ``error.code_name`` the code's name in the C header.
    """

    def __init__(self, message, code=ERR_INTERNAL):
        """An error with the library's ``message`` and negative ``code``."""
        super().__init__(message)
        self.message = message
        self.code = int(code)

    @property
    def code_name(self):
        """The code's name in fc3d_native.h, e.g. ``"FC3D_ERR_NON_FINITE"``."""
        return ERROR_NAMES.get(self.code, "FC3D_ERR_%d" % self.code)

    def __str__(self):
        """The message."""
        return self.message

    def __repr__(self):
        """``Fc3dError(message, code=...)``."""
        return "Fc3dError(%r, code=%d)" % (self.message, self.code)
