#include "nav/mapmaker/reliability.hpp"

// Fitted function and trajectory approximation: in progress on branch nav-reliability.
