// Cost and accuracy of the 3x3 symmetric eigen-decomposition behind the 3D
// constitutive update (doc/performance.md, "What is left"): deal.II's three
// eigenvectors() methods and scarp's spectral_decomposition() (for a general
// 3D tensor spectral_decomposition_general()), on 200 000 stress-like
// tensors (an isotropic -100 kPa plus a deviator of up to 1 kPa; every fourth
// nearly isotropic, deviator 1e-3 Pa, where eigenvalues nearly repeat).
// Prints nanoseconds per decomposition (the decomposition alone, median of
// 5 passes) and the largest |V diag(l) V^T - A| / |A|; then the
// exponential of plane strain-like tensors (the 2D Hencky predictor's
// exp(2 eps_e)) by decomposition against exp_symmetric()'s closed form, and
// of general 3D ones against its scaled Taylor series, with their largest
// relative differences. Asserts nothing.
//
// Usage: test_materials_benchmark_eigenvectors
#include <deal.II/base/symmetric_tensor.h>

#include <scarp/materials/spectral_decomposition.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <iomanip>
#include <iostream>
#include <random>
#include <vector>

using namespace dealii;

namespace
{
  using Decomposition = std::array<std::pair<double, Tensor<1, 3>>, 3>;

  /// results[k] = f(tensors[k]) for all k, 5 passes; the median
  /// nanoseconds per tensor.
  template <typename Result, typename Function>
  double
  median_ns(const std::vector<SymmetricTensor<2, 3>> &tensors,
            std::vector<Result>                      &results,
            const Function                           &f)
  {
    results.resize(tensors.size());
    std::vector<double> times;
    for (unsigned int pass = 0; pass < 5; ++pass)
      {
        const auto start = std::chrono::steady_clock::now();
        for (std::size_t k = 0; k < tensors.size(); ++k)
          results[k] = f(tensors[k]);
        times.push_back(std::chrono::duration<double, std::nano>(
                          std::chrono::steady_clock::now() - start)
                          .count() /
                        tensors.size());
      }
    std::sort(times.begin(), times.end());
    return times[2];
  }

  void
  measure(const std::string                        &name,
          const std::vector<SymmetricTensor<2, 3>> &tensors,
          const std::function<Decomposition(const SymmetricTensor<2, 3> &)>
            &decompose)
  {
    std::vector<Decomposition> results;
    const double               time  = median_ns(tensors, results, decompose);
    double                     worst = 0;
    for (std::size_t k = 0; k < tensors.size(); ++k)
      {
        SymmetricTensor<2, 3> B;
        for (const auto &pair : results[k])
          B += pair.first * symmetrize(outer_product(pair.second, pair.second));
        worst = std::max(worst, (B - tensors[k]).norm() / tensors[k].norm());
      }
    std::cout << "  " << std::left << std::setw(34) << name << std::right
              << std::setw(8) << std::fixed << std::setprecision(1) << time
              << " ns   worst reconstruction " << std::scientific
              << std::setprecision(2) << worst << std::endl;
  }
} // namespace

int
main()
{
  std::mt19937                           random(1);
  std::uniform_real_distribution<double> u(-1., 1.);
  std::vector<SymmetricTensor<2, 3>>     tensors(200000);
  for (std::size_t k = 0; k < tensors.size(); ++k)
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        tensors[k][i][j] =
          (i == j ? -1e5 : 0.) + 1e3 * u(random) * (k % 4 == 0 ? 1e-6 : 1.);

  std::cout << "3x3 symmetric eigen-decomposition, " << tensors.size()
            << " stress-like tensors:" << std::endl;
  const auto with = [](const SymmetricTensorEigenvectorMethod method) {
    return [method](const SymmetricTensor<2, 3> &A) {
      return eigenvectors(A, method);
    };
  };
  measure("deal.II ql_implicit_shifts",
          tensors,
          with(SymmetricTensorEigenvectorMethod::ql_implicit_shifts));
  measure("deal.II hybrid",
          tensors,
          with(SymmetricTensorEigenvectorMethod::hybrid));
  measure("deal.II jacobi",
          tensors,
          with(SymmetricTensorEigenvectorMethod::jacobi));
  measure("scarp spectral_decomposition",
          tensors,
          [](const SymmetricTensor<2, 3> &A) {
            const auto    s = scarp::materials::spectral_decomposition(A);
            Decomposition d;
            for (unsigned int i = 0; i < 3; ++i)
              d[i] = {s.values[i], s.vectors[i]};
            return d;
          });

  // The exponential of the 2D Hencky predictor, exp(2 eps_e) of a plane
  // strain-like tensor: by decomposition (eigenvalues and vectors, three
  // exponentials, compose) against exp_symmetric()'s closed form.
  std::vector<SymmetricTensor<2, 3>> plane(200000);
  for (auto &A : plane)
    {
      A[0][0] = 0.02 * u(random);
      A[1][1] = 0.02 * u(random);
      A[2][2] = 0.02 * u(random);
      A[0][1] = 0.02 * u(random);
    }
  std::vector<SymmetricTensor<2, 3>> by_decomposition, closed_form;
  const double                       t_decomposition =
    median_ns(plane, by_decomposition, [](const SymmetricTensor<2, 3> &A) {
      auto s = scarp::materials::spectral_decomposition(A);
      for (double &v : s.values)
        v = std::exp(v);
      return scarp::materials::compose(s.values, s.vectors);
    });
  const double t_closed =
    median_ns(plane, closed_form, [](const SymmetricTensor<2, 3> &A) {
      return scarp::materials::exp_symmetric(A);
    });
  double worst = 0;
  for (std::size_t k = 0; k < plane.size(); ++k)
    worst = std::max(worst,
                     (closed_form[k] - by_decomposition[k]).norm() /
                       by_decomposition[k].norm());
  std::cout << "exp of a plane symmetric tensor, " << plane.size()
            << " strain-like tensors (entries up to 0.02):" << std::endl
            << std::fixed << std::setprecision(1)
            << "  decomposition, exp, compose       " << std::setw(8)
            << t_decomposition << " ns" << std::endl
            << "  exp_symmetric (closed form)       " << std::setw(8)
            << t_closed << " ns   largest difference " << std::scientific
            << std::setprecision(2) << worst << std::endl;

  // The same for general 3D strain-like tensors (the 3D Hencky predictor):
  // decomposition against exp_symmetric()'s scaled Taylor series.
  std::vector<SymmetricTensor<2, 3>> general(200000);
  for (auto &A : general)
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        A[i][j] = 0.02 * u(random);
  std::vector<SymmetricTensor<2, 3>> general_decomposition, series;
  const double                       t_general_decomposition =
    median_ns(general,
              general_decomposition,
              [](const SymmetricTensor<2, 3> &A) {
                auto s = scarp::materials::spectral_decomposition(A);
                for (double &v : s.values)
                  v = std::exp(v);
                return scarp::materials::compose(s.values, s.vectors);
              });
  const double t_series =
    median_ns(general, series, [](const SymmetricTensor<2, 3> &A) {
      return scarp::materials::exp_symmetric(A);
    });
  worst = 0;
  for (std::size_t k = 0; k < general.size(); ++k)
    worst = std::max(worst,
                     (series[k] - general_decomposition[k]).norm() /
                       general_decomposition[k].norm());
  std::cout << std::defaultfloat << "exp of a general symmetric tensor, "
            << general.size()
            << " strain-like tensors (entries up to 0.02):" << std::endl
            << std::fixed << std::setprecision(1)
            << "  decomposition, exp, compose       " << std::setw(8)
            << t_general_decomposition << " ns" << std::endl
            << "  exp_symmetric (scaled series)     " << std::setw(8)
            << t_series << " ns   largest difference " << std::scientific
            << std::setprecision(2) << worst << std::endl;
  return 0;
}
