"""Homework variants with verified keys (``lagsolve variants``, issue 34).

``spec`` reads the request, ``generate`` draws and completes the numbers, ``key`` builds and cross-checks the
key, ``sanity`` holds the rules a variant must pass, ``yamlfile`` writes the variant's problem file,
``run`` ties them together, ``solution`` writes each variant's worked solution, ``layout`` the files of a set,
``prairielearn`` and ``moodle`` the exports.
"""
