#pragma once
// Only a forward to cli/Report.h: the hand-written JSON writer that lived here
// is gone (reports are written with nlohmann-json). Kept because
// app/plot/Plot.cpp still includes this header for writeFileAtomically;
// delete it once Plot.cpp no longer does.

#include "cli/Report.h"
