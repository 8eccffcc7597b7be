# Tests of julia/Fc3d.jl against an installed fc3d (see julia/README.md):
#
#   FC3D_LIBRARY=PREFIX/lib/libfc3d_native.so julia julia/test/runtests.jl
#
# Shared problems are read from ENV["FC3D_DATA"], else ../shared/data/siconos beside the repo.
using Test
using LinearAlgebra
using SparseArrays

include(joinpath(@__DIR__, "..", "Fc3d.jl"))
using .Fc3d

const DATA = get(ENV, "FC3D_DATA",
                 normpath(joinpath(@__DIR__, "..", "..", "..", "shared", "data", "siconos")))

# The error thrown by f(), or nothing.
function thrown(f)
    try
        f()
    catch e
        return e
    end
    return nothing
end

# Three coupled contacts (W symmetric positive definite): sticking, sliding, taking off.
function coupled()
    W = Matrix(2.0I, 9, 9)
    for (i, j, v) in ((1, 4, 0.5), (4, 7, 0.5), (2, 5, 0.2), (1, 5, 0.1), (3, 9, -0.1))
        W[i, j] = v
        W[j, i] = v
    end
    q = [-1.0, 0.2, 0.0, -2.0, 3.0, 1.0, 0.5, 0.0, 0.0]
    mu = [0.5, 0.3, 0.8]
    return W, q, mu
end

@testset "Fc3d.jl" begin
    @testset "library" begin
        @test occursin(r"^\d+\.\d+\.\d+", Fc3d.version())
        @test sizeof(Fc3d.Fc3dResult) == 32              # int, (pad), int64_t, double, double
        @test fieldoffset(Fc3d.Fc3dResult, 2) == 8
        @test fieldtypes(Fc3d.Fc3dResult) == (Cint, Int64, Cdouble, Cdouble)
    end

    @testset "single sliding contact, solver $solver" for solver in (Fc3d.NSGS, Fc3d.NSN_AC)
        # W = I, q = (-1, 2, 0), mu = 0.5: r = (1, -0.5, 0), u = (0, 1.5, 0).
        W = Matrix(1.0I, 3, 3)
        res = solve(W, [-1.0, 2.0, 0.0], [0.5]; solver = solver, tol = 1e-12, max_iter = 100)
        @test res.info == 0
        @test res.r ≈ [1.0, -0.5, 0.0] atol=1e-10
        @test res.u ≈ [0.0, 1.5, 0.0] atol=1e-10
        @test res.error <= 1e-12
        @test res.iterations >= 1 && res.iterations isa Int64
        @test res.seconds >= 0
        # Integer input is converted; the sparse path gives the same answer.
        res2 = solve(sparse([1 0 0; 0 1 0; 0 0 1]), [-1, 2, 0], [0.5]; solver = solver,
                     tol = 1e-12)
        @test res2.info == 0
        @test res2.r ≈ res.r atol=1e-12
    end

    @testset "dense and sparse agree, solver $solver" for solver in (Fc3d.NSGS, Fc3d.NSN_AC)
        W, q, mu = coupled()
        d = solve(W, q, mu; solver = solver, tol = 1e-12, max_iter = 1000)
        s = solve(sparse(W), q, mu; solver = solver, tol = 1e-12, max_iter = 1000)
        @test d.info == 0 && s.info == 0
        @test d.error <= 1e-12 && s.error <= 1e-12
        @test d.r ≈ s.r atol=1e-9
        @test d.u ≈ s.u atol=1e-9
        @test d.u ≈ W * d.r + q atol=1e-12
        @test norm(d.r[7:9]) <= 1e-10 && d.u[7] > 0                   # contact 3 takes off
        @test norm(d.r[5:6]) ≈ mu[2] * d.r[4] atol=1e-9             # contact 2 slides
        @test norm(d.r[2:3]) < mu[1] * d.r[1] && norm(d.u[1:3]) < 1e-9 # contact 1 sticks
        # A warm start from the solution: r0 is copied, not modified.
        r0 = copy(d.r)
        w = solve(W, q, mu; solver = solver, tol = 1e-10, r0 = r0)
        @test w.info == 0
        @test w.r ≈ d.r atol=1e-9
        @test r0 == d.r
        # Settings by name.
        o = solve(W, q, mu; solver = solver, options = ("tolerance" => 1e-12, "max_iter" => 1000))
        @test o.info == 0
        @test o.r ≈ d.r atol=1e-9
    end

    @testset "shared problem $name" for name in ("NESpheres_10_1", "Confeti-ex13-Fc3D-SBM")
        path = joinpath(DATA, name * ".dat")
        @test isfile(path)
        p = read_problem(path)
        nc = length(p.mu)
        @test nc > 0 && size(p.W) == (3nc, 3nc) && length(p.q) == 3nc && all(p.mu .>= 0)
        for solver in (Fc3d.NSGS, Fc3d.NSN_AC)
            res = solve(p; solver = solver, tol = 1e-8, max_iter = 100000)
            @info "$name: solver $solver, $nc contacts" res.info res.iterations res.error
            @test res.info == 0
            @test res.error <= 1e-8
            @test res.u ≈ p.W * res.r + p.q rtol=1e-10
            # The dense path on the same problem (a few hundred rows at most).
            d = solve(Matrix(p.W), p.q, p.mu; solver = solver, tol = 1e-8, max_iter = 100000)
            @test d.info == 0 && d.error <= 1e-8
        end
    end

    @testset "errors" begin
        W, q = Matrix(1.0I, 3, 3), [-1.0, 2.0, 0.0]
        e = thrown(() -> solve(W, q, [-1.0]))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_INVALID_PROBLEM &&
              occursin("mu", e.message)
        e = thrown(() -> solve(W, [-1.0, NaN, 0.0], [0.5]))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_NON_FINITE
        e = thrown(() -> solve(sparse(W), [-1.0, NaN, 0.0], [0.5]))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_NON_FINITE
        W_nan = copy(W)
        W_nan[2, 2] = NaN
        @test thrown(() -> solve(W_nan, q, [0.5])) isa Fc3dError
        e = thrown(() -> solve(W, q, [0.5]; solver = 4242))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_UNSUPPORTED_SOLVER &&
              occursin("4242", e.message)
        e = thrown(() -> solve(W, q, [0.5]; options = ("no_such_setting" => 1,)))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_INVALID_OPTION &&
              occursin("no_such_setting", e.message)
        e = thrown(() -> solve(W, q, [0.5]; tol = -1.0))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_INVALID_OPTION
        e = thrown(() -> solve(W, q, [0.5, 0.5]))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_INVALID_SIZE
        e = thrown(() -> solve(W, q, [0.5]; r0 = zeros(2)))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_INVALID_SIZE
        e = thrown(() -> read_problem("/nonexistent/problem.dat"))
        @test e isa Fc3dError && e.code == Fc3d.FC3D_ERR_IO &&
              occursin("/nonexistent/problem.dat", e.message)
        @test occursin("Fc3dError(-9)", sprint(showerror, e))
    end
end
