// lucent.h: the public API in one include.
#pragma once
#include "lucent/context.h"
#include "lucent/environment.h"
#include "lucent/error.h"
#include "lucent/image.h"
#include "lucent/material.h"
#include "lucent/medium_volume.h"
#include "lucent/mesh.h"
#include "lucent/offscreen_framebuffer.h"
#include "lucent/output_file.h"
#include "lucent/params.h"
#include "lucent/renderer.h"
#include "lucent/scene.h"
