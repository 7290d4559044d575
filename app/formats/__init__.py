"""What the service reads and writes, independent of any feature: CSV tables (:mod:`~app.formats.tables`), rows of JSON
or CSV put together from whole columns (:mod:`~app.formats.segments`), large JSON bodies parsed in pieces
(:mod:`~app.formats.jsonpieces`), raw uploads (:mod:`~app.formats.uploads`), SVG charts (:mod:`~app.formats.svg`),
and the readers of alignment files (CSV, LandXML: :mod:`~app.formats.alignment_io`) and of route geometry (GeoJSON,
GPX: :mod:`~app.formats.route_io`)."""
