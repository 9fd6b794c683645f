// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file meshquilt.h
/// Everything of the public API in one include. docs/library.md shows how to use it.

#include "meshquilt/analysis.h"
#include "meshquilt/decorate.h"
#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "meshquilt/mesh.h"
#include "meshquilt/print.h"
#include "meshquilt/quilt.h"
#include "meshquilt/report.h"
#include "meshquilt/reporter.h"
#include "meshquilt/shellmap.h"
#include "meshquilt/surface.h"
#include "meshquilt/version.h"
