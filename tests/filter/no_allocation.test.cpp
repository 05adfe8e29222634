// predict and update allocate nothing once the filter has seen its largest state: counted
// with a replaced global operator new, and Eigen's own allocations through
// EIGEN_RUNTIME_NO_MALLOC (eigen_allocation_hook.hpp counts them as allocations too).

#include "eigen_allocation_hook.hpp"
#include "replaced_operator_new.hpp"

#include <sylva/core/thread_pool.hpp>
#include <sylva/detail/compressed_region.hpp>
#include <sylva/monocular.hpp>

#include "sylva_catch.hpp"

#include "filter/monocular_rig.hpp"

using sylva_test::g_allocations;
using sylva_test::g_other_eigen_asserts;
using namespace sylva;

TEMPLATE_TEST_CASE("predict and a single update do not allocate in steady state", "[filter][allocation]",
                   (Ekf<Unicycle2D, Point2>)) {
  TestType ekf(Vec<3>(0.0, 0.0, 0.1), Mat<3, 3>::Identity() * 0.01);
  const auto r = Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));
  const auto q = Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));
  for (int i = 0; i < 200; ++i) ekf.add(i, InverseRangeBearing{}, Vec<2>(3.0 + 0.05 * i, -1.5 + 0.015 * i), r);
  // 20 steps of a predict and four updates, with allocation forbidden: how many happened.
  const auto allocationsOfSteps = [&] {
    const long before = g_allocations.load();
    Eigen::internal::set_is_malloc_allowed(false);
    for (int step = 0; step < 20; ++step) {
      ekf.predict(Vec<2>(0.5, 0.05), 0.1, q);
      for (Id id : {3, 50, 120, 199}) {
        const Vec<2> z = RangeBearing{}(ekf.robotMean(), ekf.template landmarkMean<Point2>(id)) + Vec<2>(0.01, -0.002);
        ekf.update(RangeBearing{}, id, z, r);
      }
    }
    Eigen::internal::set_is_malloc_allowed(true);
    return g_allocations.load() - before;
  };
  ekf.update(RangeBearing{}, 0, Vec<2>(3.0, -1.4), r);  // warm-up: sizes the workspace
  CHECK(allocationsOfSteps() == 0);
  // First-estimates Jacobians evaluate each model twice, without allocating either.
  ekf.setLinearizationPoint(LinearizationPoint::kFirstEstimates);
  CHECK(allocationsOfSteps() == 0);
  // The iterated update runs in the batched update's workspaces: sized by one warm-up.
  ekf.setLinearizationPoint(LinearizationPoint::kIterated);
  ekf.update(RangeBearing{}, 0, Vec<2>(3.0, -1.4), r);
  CHECK(allocationsOfSteps() == 0);
  // The invariant EKF's covariance transport has a workspace of its own: one warm-up.
  ekf.setLinearizationPoint(LinearizationPoint::kInvariant);
  ekf.update(RangeBearing{}, 0, Vec<2>(3.0, -1.4), r);
  CHECK(allocationsOfSteps() == 0);
  CHECK(g_other_eigen_asserts.load() == 0);
}

TEMPLATE_TEST_CASE("the monocular tree filter's predict and updates do not allocate in steady state", "[filter][allocation]",
                   ConstantVelocity3D, OnManifold<ConstantVelocity3D>) {
  using Filter = Ekf<TestType, InverseDepth, Point3, TreeXYZR>;
  const sylva_test::MonocularRig rig;
  const Mat<Filter::kRobotDim, Filter::kRobotDim> P0 = Mat<Filter::kRobotDim, Filter::kRobotDim>::Identity() * 1e-4;
  Filter ekf(rig.x0, P0);
  // 30 trees 6-15 m ahead: ids 0-9 stay inverse depth, 10-19 become XYZ, 20-29 XYZ-R.
  std::vector<Vec<4>> trees;
  for (int i = 0; i < 30; ++i) trees.emplace_back(6.0 + 0.3 * i, -3.0 + 0.2 * i, 0.0, 0.2 + 0.005 * i);
  for (int i = 0; i < 30; ++i) {
    const Vec<2> z = rig.xyz_model(ConstantVelocity3D::pose(rig.x0), Vec<3>(trees[i].head<3>()));
    ekf.add(i, rig.init, rig.init.measurement(z), rig.init.noise(rig.pixel));
  }
  for (int i = 10; i < 30; ++i) ekf.reparametrize(i, InverseDepthToPoint3<ConstantVelocity3D>{});
  for (int i = 20; i < 30; ++i) ekf.reparametrize(i, InverseTreeWidth(rig.camera), rig.width_model(ConstantVelocity3D::pose(rig.x0), trees[i]), rig.pixel_width);
  const auto q = Gaussian<6>::sigmas(Vec<6>::Constant(0.5));
  // Warm-up: sizes the workspaces.
  ekf.predict(Vec<0>(), 0.05, q);
  ekf.update(rig.xyz_model, 10, rig.xyz_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.template landmarkMean<Point3>(10)), rig.pixel);
  ekf.update(rig.width_model, 20, rig.width_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.template landmarkMean<TreeXYZR>(20)), rig.pixel_width);

  const auto allocationsOfSteps = [&] {
    const long before = g_allocations.load();
    Eigen::internal::set_is_malloc_allowed(false);
    for (int step = 0; step < 10; ++step) {
      ekf.predict(Vec<0>(), 0.05, q);
      ekf.update(rig.id_model, 3, rig.id_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.template landmarkMean<InverseDepth>(3)) + Vec<2>(0.3, -0.2), rig.pixel);
      ekf.update(rig.xyz_model, 15, rig.xyz_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.template landmarkMean<Point3>(15)) + Vec<2>(-0.3, 0.2), rig.pixel);
      ekf.update(rig.width_model, 25,
                 rig.width_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.template landmarkMean<TreeXYZR>(25)) + Vec<3>(0.2, 0.1, -0.2), rig.pixel_width);
    }
    Eigen::internal::set_is_malloc_allowed(true);
    return g_allocations.load() - before;
  };
  CHECK(allocationsOfSteps() == 0);
  // The observability-constrained transport has a workspace of its own: one warm-up.
  ekf.setLinearizationPoint(LinearizationPoint::kObservabilityConstrained);
  ekf.update(rig.xyz_model, 10, rig.xyz_model(ConstantVelocity3D::pose(ekf.robotMean()), ekf.template landmarkMean<Point3>(10)), rig.pixel);
  CHECK(allocationsOfSteps() == 0);
  CHECK(g_other_eigen_asserts.load() == 0);
  CHECK(ekf.template holds<TreeXYZR>(25));
}

// A map big enough that one untiled rank-24 update would make Eigen pack its panels on the
// heap (24 x 803 doubles > 128 KiB), and batches of changing size after the largest one.
TEST_CASE("batched updates do not allocate in steady state, whatever the batch size", "[filter][allocation]") {
  ThreadPool pool(2);  // its threads are made here, before anything is counted
  static_assert(detail::kParallelMinRows <= 803, "the map below must reach the threads");
  for (Parallel* parallel : {static_cast<Parallel*>(nullptr), static_cast<Parallel*>(&pool)}) {
    INFO((parallel == nullptr ? "one thread" : "a ThreadPool of 2 (n = 803: its threads take part)"));
    Ekf<Unicycle2D, Point2> ekf(Vec<3>(0.0, 0.0, 0.1), Mat<3, 3>::Identity() * 0.01);
    ekf.setParallel(parallel);
    const auto r = Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));
    const auto q = Gaussian<2>::sigmas(Vec<2>(0.05, 0.02));
    for (int i = 0; i < 400; ++i) ekf.add(i, InverseRangeBearing{}, Vec<2>(3.0 + 0.05 * i, -1.5 + 0.0075 * i), r);
    std::vector<Observation<RangeBearing>> batch;
    batch.reserve(12);
    auto observe = [&](int k, int first) {
      batch.clear();
      for (int j = 0; j < k; ++j) {
        const Id id = (first + 33 * j) % 400;
        const Vec<2> z = RangeBearing{}(ekf.robotMean(), ekf.landmarkMean<Point2>(id)) + Vec<2>(0.01, -0.002);
        batch.push_back(Observation<RangeBearing>{id, z, r});
      }
      ekf.update(RangeBearing{}, batch);
    };
    observe(12, 0);  // warm-up with the largest batch: sizes the workspaces

    const long before = g_allocations.load();
    Eigen::internal::set_is_malloc_allowed(false);
    for (int step = 0; step < 6; ++step) {
      ekf.predict(Vec<2>(0.5, 0.05), 0.1, q);
      observe(12 - step, step);
    }
    Eigen::internal::set_is_malloc_allowed(true);
    CHECK(g_allocations.load() - before == 0);
    CHECK(g_other_eigen_asserts.load() == 0);
  }
}

TEST_CASE("building a noise from a full covariance allocates nothing", "[filter][allocation]") {
  // Gaussian::covariance checks its matrix through detail::checkCovarianceMatrix, which
  // factors on the stack up to 16 x 16: a sensor may build its noise per reading.
  Mat<4, 4> cov = Mat<4, 4>::Identity();
  cov(1, 0) = cov(0, 1) = 0.3;
  Mat<13, 13> big = Mat<13, 13>::Identity() * 2.0;
  big(12, 3) = big(3, 12) = -0.5;
  const long before = g_allocations.load();
  Eigen::internal::set_is_malloc_allowed(false);
  double sum = 0.0;
  for (int i = 0; i < 10; ++i) {
    sum += Gaussian<4>::covariance(cov).covariance()(1, 0);
    sum += Gaussian<13>::covariance(big).covariance()(12, 3);
  }
  Eigen::internal::set_is_malloc_allowed(true);
  CHECK(g_allocations.load() - before == 0);
  CHECK(sum == Approx(10 * (0.3 - 0.5)));
}

TEST_CASE("the compressed EKF's local steps and global update do not allocate in steady state",
          "[filter][allocation][compressed]") {
  // detail::CompressedRegion (the kernel of the compressed policy): its workspaces grow to the
  // largest step and state seen, then every local step and global update runs in them.
  const int n = 3 + 2 * 40;
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n);
  for (int i = 1; i < n; ++i) P(i, i - 1) = 0.1;  // lower triangle, as the filter stores it
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  detail::CompressedRegion region;
  region.begin(7);
  const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() + 0.01 * Eigen::Matrix3d::Ones();
  // Up to 4 rows the accumulators take rank-one updates in place; 6 rows go through the
  // staged products (CompressedRegion::stageUpdate): both paths are run.
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(6, 7), W = Eigen::MatrixXd::Zero(7, 6);
  H(0, 0) = H(1, 3) = H(2, 5) = H(3, 6) = H(4, 1) = H(5, 2) = 1.0;
  W = 0.1 * H.transpose();
  const Eigen::LLT<Eigen::MatrixXd> S(Eigen::MatrixXd::Identity(4, 4) * 2.0);
  const Eigen::LLT<Eigen::MatrixXd> S6(Eigen::MatrixXd::Identity(6, 6) * 2.0);
  const Eigen::VectorXd nu = Eigen::VectorXd::Constant(6, 0.05);
  const Eigen::LLT<Eigen::MatrixXd> S2(Eigen::MatrixXd::Identity(2, 2) * 2.0);
  const auto update = [&](int m, const Eigen::LLT<Eigen::MatrixXd>& llt) {
    auto HphiT = region.hphiTransposed(m);
    HphiT.noalias() = region.phiTransposed() * H.topRows(m).transpose();
    region.stageUpdate(llt.matrixL(), nu.head(m), W.leftCols(m));
    region.commitUpdate();
  };
  const auto stepsWithTwoRows = [&] {
    for (int k = 0; k < 5; ++k) {
      region.predictRobot<3>(J);
      update(4, S);
      update(2, S2);
      update(6, S6);
    }
    region.globalUpdate(P, x);
  };
  stepsWithTwoRows();  // warm-up: sizes the workspaces
  const long before = g_allocations.load();
  Eigen::internal::set_is_malloc_allowed(false);
  stepsWithTwoRows();
  Eigen::internal::set_is_malloc_allowed(true);
  CHECK(g_allocations.load() - before == 0);
  CHECK(x.allFinite());
  CHECK(g_other_eigen_asserts.load() == 0);
}
