// SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
// version 2 (the same licence as LAMMPS); see the LICENSE file.
//
// Grid reference for the Kelvin-Helmholtz test of McNally, Lyra & Passy (2012, ApJS 201, 18):
// 2D compressible Euler equations, gamma 5/3, periodic unit box, N x N cells.
//
// Scheme: second-order MUSCL-Hancock finite volumes (Toro 2009, Riemann Solvers and Numerical
// Methods for Fluid Dynamics, 3rd ed., sec. 14.4): piecewise-linear primitive variables
// W = (rho, u_n, u_t, p) with monotonised-central (MC) limited slopes
//   Delta_i = minmod(2 (W_i - W_{i-1}), 2 (W_{i+1} - W_i), (W_{i+1} - W_{i-1}) / 2),
// boundary values W_i -/+ Delta_i / 2 advanced by half a step with the primitive equations
//   W_i^{L,R} <- W_i^{L,R} - dt / (2 dx) A(W_i) Delta_i             (Toro 2009, eq. 14.45),
// and the HLLC Riemann solver at each face (Toro 2009, sec. 10.4, eqs. 10.37-10.39 with the
// wave speeds of Davis 1988, Toro eq. 10.48). The two directions are Strang split
// (Strang 1968): X Y in even steps, Y X in odd ones. CFL 0.4 on max(|u|, |v|) + c.
//
// Initial state: McNally et al. (2012) eqs. 1-5 sampled at the cell centres.
// Output: t and the mode amplitude M of their eqs. 6-9 every dtout up to tend:
//   s = sum v_y sin(4 pi x) w V, c = sum v_y cos(4 pi x) w V, d = sum w V,
//   M = 2 sqrt((s/d)^2 + (c/d)^2),  w = exp(-4 pi |y - 1/4|) (y < 1/2),
//   exp(-4 pi |(1 - y) - 1/4|) (y >= 1/2),  V = cell area.
//
// Usage: kh_grid N [tend 2] [dtout 0.01] [cfl 0.4]   (t M on stdout; threads: OMP_NUM_THREADS)

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

const double GAMMA = 5.0 / 3.0;
const double PI = 3.14159265358979323846;

struct Prim {
  double r, un, ut, p;
};

inline double minmod3(double a, double b, double c)
{
  if (a > 0.0 && b > 0.0 && c > 0.0) return std::min(a, std::min(b, c));
  if (a < 0.0 && b < 0.0 && c < 0.0) return std::max(a, std::max(b, c));
  return 0.0;
}

// MC limiter (van Leer 1977)
inline double mc(double dm, double dp)
{
  return minmod3(2.0 * dm, 2.0 * dp, 0.5 * (dm + dp));
}

// HLLC flux (Toro 2009, sec. 10.4) of (rho, rho u_n, rho u_t, E) in the normal direction
inline void hllc(const Prim &L, const Prim &R, double F[4])
{
  const double cL = std::sqrt(GAMMA * L.p / L.r), cR = std::sqrt(GAMMA * R.p / R.r);
  const double SL = std::min(L.un - cL, R.un - cR), SR = std::max(L.un + cL, R.un + cR);
  const double EL = L.p / (GAMMA - 1.0) + 0.5 * L.r * (L.un * L.un + L.ut * L.ut);
  const double ER = R.p / (GAMMA - 1.0) + 0.5 * R.r * (R.un * R.un + R.ut * R.ut);
  const double FL[4] = {L.r * L.un, L.r * L.un * L.un + L.p, L.r * L.un * L.ut, (EL + L.p) * L.un};
  const double FR[4] = {R.r * R.un, R.r * R.un * R.un + R.p, R.r * R.un * R.ut, (ER + R.p) * R.un};
  if (SL >= 0.0) {
    for (int k = 0; k < 4; k++) F[k] = FL[k];
    return;
  }
  if (SR <= 0.0) {
    for (int k = 0; k < 4; k++) F[k] = FR[k];
    return;
  }
  const double mL = L.r * (SL - L.un), mR = R.r * (SR - R.un);
  const double Ss = (R.p - L.p + L.un * mL - R.un * mR) / (mL - mR);    // Toro eq. 10.37
  const Prim &K = Ss >= 0.0 ? L : R;
  const double S = Ss >= 0.0 ? SL : SR;
  const double E = Ss >= 0.0 ? EL : ER;
  const double *FK = Ss >= 0.0 ? FL : FR;
  const double f = K.r * (S - K.un) / (S - Ss);    // Toro eq. 10.39
  const double Us[4] = {f, f * Ss, f * K.ut,
                        f * (E / K.r + (Ss - K.un) * (Ss + K.p / (K.r * (S - K.un))))};
  const double UK[4] = {K.r, K.r * K.un, K.r * K.ut, E};
  for (int k = 0; k < 4; k++) F[k] = FK[k] + S * (Us[k] - UK[k]);    // Toro eq. 10.38
}

// one MUSCL-Hancock step along a periodic line of n cells: q[k][i], k = rho, m_n, m_t, E
void sweep(int n, double dtdx, std::vector<double> *q, std::vector<Prim> &w, std::vector<Prim> &wl,
           std::vector<Prim> &wr, std::vector<double> &flux)
{
  // primitives with two periodic ghosts on each side: w[i + 2] is cell i
  for (int i = -2; i < n + 2; i++) {
    const int j = (i + n) % n;
    const double r = q[0][j], un = q[1][j] / r, ut = q[2][j] / r;
    w[i + 2] = {r, un, ut, (GAMMA - 1.0) * (q[3][j] - 0.5 * r * (un * un + ut * ut))};
  }
  // limited slopes and half-step evolved boundary values of cells -1 .. n
  for (int i = -1; i <= n; i++) {
    const Prim &a = w[i + 1], &b = w[i + 2], &c = w[i + 3];
    const double dr = mc(b.r - a.r, c.r - b.r), dun = mc(b.un - a.un, c.un - b.un);
    const double dut = mc(b.ut - a.ut, c.ut - b.ut), dp = mc(b.p - a.p, c.p - b.p);
    // A(W) Delta for the primitive Euler equations (Toro 2009, eq. 14.45)
    const double h = 0.5 * dtdx;
    const double er = h * (b.un * dr + b.r * dun), eun = h * (b.un * dun + dp / b.r);
    const double eut = h * (b.un * dut), ep = h * (GAMMA * b.p * dun + b.un * dp);
    wl[i + 1] = {b.r - 0.5 * dr - er, b.un - 0.5 * dun - eun, b.ut - 0.5 * dut - eut,
                 b.p - 0.5 * dp - ep};
    wr[i + 1] = {b.r + 0.5 * dr - er, b.un + 0.5 * dun - eun, b.ut + 0.5 * dut - eut,
                 b.p + 0.5 * dp - ep};
  }
  // flux through face i - 1/2 for i = 0 .. n: left state wr of cell i-1, right wl of cell i
  for (int i = 0; i <= n; i++) hllc(wr[i], wl[i + 1], &flux[4 * i]);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 4; k++) q[k][i] -= dtdx * (flux[4 * (i + 1) + k] - flux[4 * i + k]);
}

struct Grid {
  int n;
  double dx;
  std::vector<double> rho, mx, my, en;    // conserved, index i + n j (x = (i + 1/2) dx)

  explicit Grid(int n_) : n(n_), dx(1.0 / n_), rho(n_ * n_), mx(n_ * n_), my(n_ * n_), en(n_ * n_)
  {
  }

  // sweep along x (dir 0) or y (dir 1); the lines are independent (OpenMP threads)
  void sweep_dir(int dir, double dt)
  {
#pragma omp parallel
    {
      std::vector<double> line[4];
      for (auto &l : line) l.resize(n);
      std::vector<Prim> w(n + 4), wl(n + 2), wr(n + 2);
      std::vector<double> flux(4 * (n + 1));
#pragma omp for schedule(static)
      for (int a = 0; a < n; a++) {
        for (int b = 0; b < n; b++) {
          const int c = dir == 0 ? b + n * a : a + n * b;
          line[0][b] = rho[c];
          line[1][b] = dir == 0 ? mx[c] : my[c];
          line[2][b] = dir == 0 ? my[c] : mx[c];
          line[3][b] = en[c];
        }
        sweep(n, dt / dx, line, w, wl, wr, flux);
        for (int b = 0; b < n; b++) {
          const int c = dir == 0 ? b + n * a : a + n * b;
          rho[c] = line[0][b];
          (dir == 0 ? mx[c] : my[c]) = line[1][b];
          (dir == 0 ? my[c] : mx[c]) = line[2][b];
          en[c] = line[3][b];
        }
      }
    }
  }

  double max_speed() const
  {
    double s = 0.0;
    for (int c = 0; c < n * n; c++) {
      const double u = mx[c] / rho[c], v = my[c] / rho[c];
      const double p = (GAMMA - 1.0) * (en[c] - 0.5 * rho[c] * (u * u + v * v));
      s = std::max(s, std::max(std::fabs(u), std::fabs(v)) + std::sqrt(GAMMA * p / rho[c]));
    }
    return s;
  }
};

// McNally et al. (2012) eqs. 1-5
void initial_state(Grid &g)
{
  const double rho1 = 1.0, rho2 = 2.0, U1 = 0.5, U2 = -0.5, L = 0.025, P0 = 2.5;
  const double rhom = 0.5 * (rho1 - rho2), Um = 0.5 * (U1 - U2);
  for (int j = 0; j < g.n; j++) {
    const double y = (j + 0.5) * g.dx;
    double r, u;
    if (y < 0.25) {
      r = rho1 - rhom * std::exp((y - 0.25) / L);
      u = U1 - Um * std::exp((y - 0.25) / L);
    } else if (y < 0.5) {
      r = rho2 + rhom * std::exp((0.25 - y) / L);
      u = U2 + Um * std::exp((0.25 - y) / L);
    } else if (y < 0.75) {
      r = rho2 + rhom * std::exp((y - 0.75) / L);
      u = U2 + Um * std::exp((y - 0.75) / L);
    } else {
      r = rho1 - rhom * std::exp((0.75 - y) / L);
      u = U1 - Um * std::exp((0.75 - y) / L);
    }
    for (int i = 0; i < g.n; i++) {
      const double x = (i + 0.5) * g.dx;
      const double v = 0.01 * std::sin(4.0 * PI * x);
      const int c = i + g.n * j;
      g.rho[c] = r;
      g.mx[c] = r * u;
      g.my[c] = r * v;
      g.en[c] = P0 / (GAMMA - 1.0) + 0.5 * r * (u * u + v * v);
    }
  }
}

// McNally et al. (2012) eqs. 6-9 over the cells (equal volumes)
double mode_amplitude(const Grid &g)
{
  double s = 0.0, c = 0.0, d = 0.0;
  for (int j = 0; j < g.n; j++) {
    const double y = (j + 0.5) * g.dx;
    const double w = y < 0.5 ? std::exp(-4.0 * PI * std::fabs(y - 0.25))
                             : std::exp(-4.0 * PI * std::fabs((1.0 - y) - 0.25));
    for (int i = 0; i < g.n; i++) {
      const double x = (i + 0.5) * g.dx;
      const int k = i + g.n * j;
      const double vy = g.my[k] / g.rho[k];
      s += vy * std::sin(4.0 * PI * x) * w;
      c += vy * std::cos(4.0 * PI * x) * w;
      d += w;
    }
  }
  return 2.0 * std::sqrt((s / d) * (s / d) + (c / d) * (c / d));
}

}    // namespace

int main(int argc, char **argv)
{
  if (argc < 2) {
    std::fprintf(stderr, "usage: kh_grid N [tend 2] [dtout 0.01] [cfl 0.4]\n");
    return 1;
  }
  const int n = std::atoi(argv[1]);
  const double tend = argc > 2 ? std::atof(argv[2]) : 2.0;
  const double dtout = argc > 3 ? std::atof(argv[3]) : 0.01;
  const double cfl = argc > 4 ? std::atof(argv[4]) : 0.4;
  if (n < 8 || tend <= 0.0 || dtout <= 0.0 || cfl <= 0.0 || cfl > 1.0) {
    std::fprintf(stderr, "kh_grid: need N >= 8, tend > 0, dtout > 0, 0 < cfl <= 1\n");
    return 1;
  }
  Grid g(n);
  initial_state(g);
  const int nout = (int) std::lround(tend / dtout);
  double t = 0.0;
  long step = 0;
  std::printf("%.6f %.10e\n", t, mode_amplitude(g));
  for (int k = 1; k <= nout; k++) {
    const double tout = k * dtout;
    while (t < tout - 1e-12) {
      double dt = cfl * g.dx / g.max_speed();
      if (t + dt > tout) dt = tout - t;
      if (step % 2 == 0) {
        g.sweep_dir(0, dt);
        g.sweep_dir(1, dt);
      } else {
        g.sweep_dir(1, dt);
        g.sweep_dir(0, dt);
      }
      t += dt;
      step++;
    }
    t = tout;
    std::printf("%.6f %.10e\n", t, mode_amplitude(g));
    std::fflush(stdout);
  }
  std::fprintf(stderr, "kh_grid: N %d, %ld steps to t = %g\n", n, step, t);
  return 0;
}
