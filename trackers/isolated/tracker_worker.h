// The worker process's side of an IsolatedTracker.
#pragma once

#include <vector>

#include "core/marker_spec.h"
#include "trackers/tracker.h"

namespace markerbench {

// Sends an empty ready message on `fd`, then answers each request with `tracker` until the
// peer closes. `markers` are those requests may name. Returns the worker's exit status: 0
// when the peer closed, 2 for a malformed request or an unknown marker.
int ServeTrackerWorker(Tracker* tracker, const std::vector<MarkerSpec>& markers, int fd);

}  // namespace markerbench
