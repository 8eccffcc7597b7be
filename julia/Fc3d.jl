"""
    Fc3d

Julia bindings of fc3d's native entry (`fc3d_native.h`): the discrete 3D frictional contact
problem FC(W, q, mu) — find `r, u` in R^(3nc) with `u = W r + q`, Signorini contact and Coulomb
friction at every contact (components ordered normal, tangent 1, tangent 2).

The library is `ENV["FC3D_LIBRARY"]` (a path or a name), else `"libfc3d_native"` found on the
system's library path; it is opened on first use.

    include("Fc3d.jl"); using .Fc3d
    res = solve([1.0 0 0; 0 1 0; 0 0 1], [-1.0, 2, 0], [0.5]; solver=500, tol=1e-10)
    res.r   # [1.0, -0.5, 0.0]: the contact slides, res.u == [0.0, 1.5, 0.0]

Failures (rejected input, unknown solver, unreadable file) throw an [`Fc3dError`](@ref)
carrying the library's code and message. A solver that runs but does not reach the tolerance
does not throw: `info` is then 1 (iteration limit), 2 (time budget) or 3 (SOCLCP: relaxed
solution not Coulomb).
"""
module Fc3d

using Libdl
using SparseArrays

export solve, read_problem, Problem, Fc3dError, version

# ---------------------------------------------------------------------------------------------
# Constants of fc3d_native.h.

const FC3D_OK = 0
const FC3D_NOT_CONVERGED = 1
const FC3D_TIME_BUDGET_EXHAUSTED = 2
const FC3D_RELAXED_NOT_COULOMB = 3
const FC3D_ERR_NULL_POINTER = -1
const FC3D_ERR_INVALID_SIZE = -2
const FC3D_ERR_INVALID_STORAGE = -3
const FC3D_ERR_NON_FINITE = -4
const FC3D_ERR_INVALID_OPTION = -5
const FC3D_ERR_UNSUPPORTED_SOLVER = -6
const FC3D_ERR_INVALID_PROBLEM = -7
const FC3D_ERR_PARSE = -8
const FC3D_ERR_IO = -9
const FC3D_ERR_INTERNAL = -99

# Solver ids (Siconos' SICONOS_FRICTION_3D_* numbers).
const NSGS = 500
const PROX = 502
const NSN_AC = 504
const NSN_FB = 513
const NSN_NM = 520
const ADMM = 523

"""
    Fc3dError(code, message)

A call the library rejected: `code` is its negative `FC3D_ERR_*` code, `message` its
`fc3d_last_error_message()` (or the binding's own message for size checks done in Julia).
"""
struct Fc3dError <: Exception
    code::Int
    message::String
end

Base.showerror(io::IO, e::Fc3dError) = print(io, "Fc3dError(", e.code, "): ", e.message)

# struct Fc3dResult { int info; int64_t iterations; double error; double seconds; }
# (an isbits struct has C's layout: 4 bytes of padding after `info`, 32 bytes in all).
struct Fc3dResult
    info::Cint
    iterations::Int64
    error::Cdouble
    seconds::Cdouble
end

# ---------------------------------------------------------------------------------------------
# The library, opened on first use; functions called through dlsym'd pointers so that the path
# can come from the environment at run time.

const _handle = Ref{Ptr{Cvoid}}(C_NULL)
const _lock = ReentrantLock()

"""Path or name of the library: `ENV["FC3D_LIBRARY"]`, else `"libfc3d_native"`."""
library_path() = get(ENV, "FC3D_LIBRARY", "libfc3d_native")

function _lib()
    _handle[] != C_NULL && return _handle[]
    lock(_lock) do
        if _handle[] == C_NULL
            _handle[] = Libdl.dlopen(library_path())
        end
    end
    return _handle[]
end

_sym(name::Symbol) = Libdl.dlsym(_lib(), name)

# ---------------------------------------------------------------------------------------------
# Errors and version.

"""The message of the last failed fc3d call on this thread (`""` if none)."""
function last_error_message()
    p = ccall(_sym(:fc3d_last_error_message), Ptr{Cchar}, ())
    return p == C_NULL ? "" : unsafe_string(p)
end

"""The code of the last failed fc3d call on this thread (0 if none)."""
last_error_code() = Int(ccall(_sym(:fc3d_last_error_code), Cint, ()))

_throw_last() = throw(Fc3dError(last_error_code(), last_error_message()))

"""The library's version, e.g. `"0.2.0"`."""
version() = unsafe_string(ccall(_sym(:fc3d_version), Ptr{Cchar}, ()))

# ---------------------------------------------------------------------------------------------
# Settings.

# New settings of `solver` with the options given (`nothing`: the solver's default); the caller
# frees them with fc3d_settings_free.
function _settings(solver, tol, max_iter, time_budget, local_solver, options)
    s = ccall(_sym(:fc3d_settings_new), Ptr{Cvoid}, (Cint,), Cint(solver))
    s == C_NULL && _throw_last()
    try
        _check(tol === nothing ? 0 :
               ccall(_sym(:fc3d_settings_set_tolerance), Cint, (Ptr{Cvoid}, Cdouble),
                     s, Float64(tol)))
        _check(max_iter === nothing ? 0 :
               ccall(_sym(:fc3d_settings_set_max_iter), Cint, (Ptr{Cvoid}, Int64),
                     s, Int64(max_iter)))
        _check(time_budget === nothing ? 0 :
               ccall(_sym(:fc3d_settings_set_time_budget), Cint, (Ptr{Cvoid}, Cdouble),
                     s, Float64(time_budget)))
        _check(local_solver === nothing ? 0 :
               ccall(_sym(:fc3d_settings_set_local_solver), Cint, (Ptr{Cvoid}, Cint),
                     s, Cint(local_solver)))
        for (name, value) in (options isa NamedTuple ? pairs(options) : options)
            _check(ccall(_sym(:fc3d_settings_set), Cint, (Ptr{Cvoid}, Cstring, Cdouble),
                         s, String(name), Float64(value)))
        end
    catch
        ccall(_sym(:fc3d_settings_free), Cvoid, (Ptr{Cvoid},), s)
        rethrow()
    end
    return s
end

_check(code) = code < 0 ? _throw_last() : Int(code)

# ---------------------------------------------------------------------------------------------
# Solving.

_size_error(msg) = throw(Fc3dError(FC3D_ERR_INVALID_SIZE, msg))

function _vectors(n_rows, q, mu, r0)
    nc = length(mu)
    n = 3nc
    n_rows == n || _size_error("W has $n_rows rows, want 3 length(mu) = $n")
    length(q) == n || _size_error("length(q) = $(length(q)), want 3 length(mu) = $n")
    r = r0 === nothing ? zeros(Float64, n) : Vector{Float64}(r0)  # a copy: r0 is not changed
    length(r) == n || _size_error("length(r0) = $(length(r)), want 3 length(mu) = $n")
    return nc, convert(Vector{Float64}, q), convert(Vector{Float64}, mu), r, zeros(Float64, n)
end

# Runs `call(settings, result_ref)` with settings made from the keywords, then frees them.
function _run(call, r, u; solver, tol, max_iter, time_budget, local_solver, options)
    s = _settings(solver, tol, max_iter, time_budget, local_solver, options)
    result = Ref(Fc3dResult(0, 0, 0.0, 0.0))
    code = try
        call(s, result)
    finally
        ccall(_sym(:fc3d_settings_free), Cvoid, (Ptr{Cvoid},), s)
    end
    _check(code)
    res = result[]
    return (r = r, u = u, info = Int(res.info), error = res.error,
            iterations = res.iterations, seconds = res.seconds)
end

"""
    solve(W, q, mu; solver=500, tol=nothing, max_iter=nothing, time_budget=nothing,
          local_solver=nothing, r0=nothing, options=())

Solves FC(W, q, mu) with `W` a dense matrix (any `AbstractMatrix`, copied to a
`Matrix{Float64}` when it is not one) or a `SparseMatrixCSC` (passed as 0-based `Int64`
triplets), `q` of length `3nc`, `mu` of length `nc`. Options left at `nothing` keep the solver's
(Siconos') defaults; `options` are further settings by name (pairs, a `Dict` or a NamedTuple),
e.g. `("iparam[7]" => 1, "dparam[3]" => 0.5)`, applied in order by `fc3d_settings_set`. `r0`
is the initial reaction (zeros by default; it is not modified).

Returns a NamedTuple `(r, u, info, error, iterations, seconds)`: `info` 0 converged, 1
iteration limit, 2 time budget spent, 3 relaxed solution not Coulomb (SOCLCP); `error` is the
natural-map error of the returned `(r, u)`. Throws [`Fc3dError`](@ref) when the input or a
setting is rejected.
"""
function solve(W::AbstractMatrix{<:Real}, q::AbstractVector{<:Real}, mu::AbstractVector{<:Real};
               solver::Integer = NSGS, tol = nothing, max_iter = nothing, time_budget = nothing,
               local_solver = nothing, r0 = nothing, options = ())
    size(W, 1) == size(W, 2) || _size_error("W is $(size(W, 1)) x $(size(W, 2)), not square")
    nc, q, mu, r, u = _vectors(size(W, 1), q, mu, r0)
    w = W isa Matrix{Float64} ? W : Matrix{Float64}(W)   # column-major, as C wants
    return _run(r, u; solver, tol, max_iter, time_budget, local_solver, options) do s, result
        ccall(_sym(:fc3d_solve_dense), Cint,
              (Int64, Ptr{Cdouble}, Ptr{Cdouble}, Ptr{Cdouble}, Ptr{Cdouble}, Ptr{Cdouble},
               Ptr{Cvoid}, Ref{Fc3dResult}),
              Int64(nc), w, q, mu, r, u, s, result)
    end
end

function solve(W::SparseMatrixCSC{<:Real}, q::AbstractVector{<:Real}, mu::AbstractVector{<:Real};
               solver::Integer = NSGS, tol = nothing, max_iter = nothing, time_budget = nothing,
               local_solver = nothing, r0 = nothing, options = ())
    size(W, 1) == size(W, 2) || _size_error("W is $(size(W, 1)) x $(size(W, 2)), not square")
    nc, q, mu, r, u = _vectors(size(W, 1), q, mu, r0)
    I, J, V = findnz(W)
    rows = Int64[i - 1 for i in I]          # 0-based
    cols = Int64[j - 1 for j in J]
    values = Vector{Float64}(V)
    n_entries = Int64(length(values))
    return _run(r, u; solver, tol, max_iter, time_budget, local_solver, options) do s, result
        ccall(_sym(:fc3d_solve_coo), Cint,
              (Int64, Int64, Ptr{Int64}, Ptr{Int64}, Ptr{Cdouble}, Ptr{Cdouble}, Ptr{Cdouble},
               Ptr{Cdouble}, Ptr{Cdouble}, Ptr{Cvoid}, Ref{Fc3dResult}),
              Int64(nc), n_entries, rows, cols, values, q, mu, r, u, s, result)
    end
end

# ---------------------------------------------------------------------------------------------
# Problems from files.

"""
    Problem(W, q, mu)

A problem FC(W, q, mu) as Julia data (`W` sparse, as read from a file). `solve(p; ...)` solves
it.
"""
struct Problem
    W::SparseMatrixCSC{Float64,Int}
    q::Vector{Float64}
    mu::Vector{Float64}
end

Base.show(io::IO, p::Problem) =
    print(io, "Fc3d.Problem(", length(p.mu), " contacts, ", nnz(p.W), " entries in W)")

"""
    read_problem(path) -> Problem

Reads a Siconos `.dat` problem (or FCLIB `.hdf5` when the library is built with FCLIB) with
`fc3d_problem_read`; throws [`Fc3dError`](@ref) (code `FC3D_ERR_IO`, `FC3D_ERR_PARSE`, ...)
when it cannot be read.
"""
function read_problem(path::AbstractString)
    p = ccall(_sym(:fc3d_problem_read), Ptr{Cvoid}, (Cstring,), String(path))
    p == C_NULL && _throw_last()
    try
        nc = ccall(_sym(:fc3d_problem_contacts), Int64, (Ptr{Cvoid},), p)
        nz = ccall(_sym(:fc3d_problem_nnz), Int64, (Ptr{Cvoid},), p)
        (nc < 0 || nz < 0) && _throw_last()
        n = 3nc
        row_ptr = zeros(Int64, n + 1)
        col_idx = zeros(Int64, nz)
        values = zeros(Float64, nz)
        q = zeros(Float64, n)
        mu = zeros(Float64, nc)
        _check(ccall(_sym(:fc3d_problem_get), Cint,
                     (Ptr{Cvoid}, Ptr{Int64}, Ptr{Int64}, Ptr{Cdouble}, Ptr{Cdouble},
                      Ptr{Cdouble}),
                     p, row_ptr, col_idx, values, q, mu))
        # Compressed rows (0-based) to triplets (1-based), duplicates summed by `sparse`.
        rows = Vector{Int}(undef, nz)
        for i in 1:n, k in (row_ptr[i] + 1):row_ptr[i + 1]
            rows[k] = i
        end
        W = sparse(rows, Int[j + 1 for j in col_idx], values, n, n)
        return Problem(W, q, mu)
    finally
        ccall(_sym(:fc3d_problem_free), Cvoid, (Ptr{Cvoid},), p)
    end
end

solve(p::Problem; kwargs...) = solve(p.W, p.q, p.mu; kwargs...)

end # module
