// The estimate of the wall time left on the progress line, for a fresh run
// and for a resumed one, against the arithmetic of a constant pace.

#include <scarp/postprocess/run_progress.h>

#include "../scenes/check.h"

using scarp::postprocess::remaining_wall_time;

int
main()
{
  // The estimate is one difference, one product and one quotient of the
  // inputs: 1e-12 of the expected value is rounding only (15.0 - 14.9 is
  // 0.1 to 1e-14 relative in binary), 1e-9 s where the value is 0.
  const double rel = 1e-12, tol = 1e-9;
  // A fresh run: 100 s of wall time took it from 0 to 10 s of 40 s, so
  // 30 s are left at 10 s of wall time per simulated second.
  CHECK_CLOSE(remaining_wall_time(100., 0., 10., 40.), 300., rel * 300.);
  // A run resumed at t = 14.9 s that reached 15.0 s in 100 s of wall
  // time: 25 s left at 1000 s per simulated second. Counting from t = 0
  // (the estimate before this one) gives 166.7 s instead.
  CHECK_CLOSE(remaining_wall_time(100., 14.9, 15.0, 40.), 2.5e4, rel * 2.5e4);
  // Nothing simulated yet (the first progress line of a resumed run) and
  // past the end: no estimate.
  CHECK_CLOSE(remaining_wall_time(5., 14.9, 14.9, 40.), 0., tol);
  CHECK_CLOSE(remaining_wall_time(5., 0., 41., 40.), 0., tol);
  return scenes_test::finish();
}
