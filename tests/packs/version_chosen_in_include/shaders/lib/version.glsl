// One #version per loader, chosen by the loader's macros: Iris's preprocessor resolves this
// before the driver reads the text, so the driver sees one #version, first.
#ifdef IRIS_VERSION
    #version 330 compatibility
#else
    #version 120
#endif
