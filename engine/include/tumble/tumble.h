#pragma once
/// Everything an embedding application needs.

#include "tumble/body.h"
#include "tumble/core/error.h"
#include "tumble/core/math.h"
#include "tumble/world.h"
