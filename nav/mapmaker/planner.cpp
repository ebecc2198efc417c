#include "nav/mapmaker/planner.hpp"

// Implementation in progress (helper branch nav-planner).
