// navfn-smt: the plugin is linked into the driver directly; nothing is exported.
#ifndef NAVFN_SMT_PLUGIN_STUB_CLASS_LIST_MACROS_HPP_
#define NAVFN_SMT_PLUGIN_STUB_CLASS_LIST_MACROS_HPP_
#define PLUGINLIB_EXPORT_CLASS(a, b)
#endif
