"""Vehicle forms: the shapes a vehicle takes in a request or in the catalog -- a record
(:mod:`~app.vehicle_forms.schemas`), a builder spec (:mod:`~app.vehicle_forms.builder_schemas`), a combination
(:mod:`~app.vehicle_forms.combination_schemas`), a combination spec
(:mod:`~app.vehicle_forms.combination_builder_schemas`) -- and the one function per form that turns it into the
engine's record (:mod:`~app.vehicle_forms.build`).

A storey below the features: the vehicles feature (routes, builder endpoints, the resolution of a computation's
vehicle), the catalog (which checks a saved vehicle with these forms) and every computation's schema import it;
it imports no feature, so the catalog and the vehicles feature need not import each other.
"""
