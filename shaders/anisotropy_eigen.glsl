#version 450 core
// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations
// (a fixed number of sweeps: convergence is quadratic, and a covariance of
// neighbours needs no more than float precision). A library without a stage,
// linked into anisotropy_shape.comp.glsl.

const int JACOBI_SWEEPS = 5;

// Zeroes a[p][q] by the rotation P (P_pp = P_qq = c, P_pq = s, P_qp = -s;
// Numerical Recipes' sign convention): a <- P^T a P, v <- v P.
void jacobi_rotate(inout mat3 a, inout mat3 v, int p, int q)
{
    float apq = a[q][p];
    if (apq == 0.0)
        return;
    float theta = (a[q][q] - a[p][p]) / (2.0 * apq);
    // The smaller root of t^2 + 2 theta t - 1 = 0: the rotation by at most 45 degrees.
    float t = (theta >= 0.0 ? 1.0 : -1.0) / (abs(theta) + sqrt(theta * theta + 1.0));
    float c = inversesqrt(t * t + 1.0);
    mat3 r = mat3(1.0);
    r[p][p] = c;
    r[q][q] = c;
    r[q][p] = t * c;    // column q, row p
    r[p][q] = -t * c;
    a = transpose(r) * a * r;
    v = v * r;
}

// The eigenvalues of symmetric `a`, largest first, and their unit
// eigenvectors as the columns of `vectors`, in the same order.
void symmetric_eigen(mat3 a, out vec3 values, out mat3 vectors)
{
    mat3 v = mat3(1.0);
    for (int sweep = 0; sweep < JACOBI_SWEEPS; sweep++) {
        jacobi_rotate(a, v, 0, 1);
        jacobi_rotate(a, v, 0, 2);
        jacobi_rotate(a, v, 1, 2);
    }
    values = vec3(a[0][0], a[1][1], a[2][2]);
    vectors = v;
    // Three compare-and-swaps sort three values.
    for (int pass = 0; pass < 3; pass++) {
        int i = pass == 1 ? 1 : 0;
        if (values[i] < values[i + 1]) {
            values.xyz = i == 0 ? values.yxz : values.xzy;
            vectors = i == 0 ? mat3(vectors[1], vectors[0], vectors[2]) : mat3(vectors[0], vectors[2], vectors[1]);
        }
    }
}
