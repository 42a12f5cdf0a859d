// method_list.h: the registered rendering methods, one line each: LUCENT_METHOD(identifier), where the method's
// folder defines `const MethodInfo <identifier>_info` (data, no GL) and `create_<identifier>(...)` (method.h).
// The first is the default. Included twice with different LUCENT_METHOD definitions (method_registry.cpp,
// method_factory.cpp); adding a method is one line here and its folder.
LUCENT_METHOD(radiosity_maps)
LUCENT_METHOD(per_pixel)
LUCENT_METHOD(voxel_paths)
LUCENT_METHOD(texture_space_is)
LUCENT_METHOD(hybrid)
LUCENT_METHOD(local_global)
LUCENT_METHOD(layered_stm)
LUCENT_METHOD(layered_parallax)
LUCENT_METHOD(diffuse_wrap)
LUCENT_METHOD(screen_space)
LUCENT_METHOD(random_walk)
