// Placeholder so that a library group with no sources yet still builds.
namespace softsim { inline void empty_group_placeholder() {} }
