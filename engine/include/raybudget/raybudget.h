// raybudget: the one header an integrating engine includes.
#pragma once
#include "raybudget/camera.h"
#include "raybudget/core.h"
#include "raybudget/error.h"
#include "raybudget/image_io.h"
#include "raybudget/renderer.h"
#include "raybudget/scene.h"
#include "raybudget/scene_builder.h"
#include "raybudget/stats.h"
