//! The tangents of a normal-mapped model: the file's where it gives them, MikkTSpace's elsewhere
//! (as glTF asks where a mesh has none).

use super::model::Model;

impl Model {
    /// Fills [`Model::tangents`] where a material has a normal map: `given` (one per vertex, in
    /// the vertices' order; a w of 0 where the file gave none) where it holds one, MikkTSpace's
    /// (as glTF asks where a mesh has none) elsewhere. A model without normal maps keeps none.
    pub fn generate_tangents(&mut self, given: Option<Vec<[f32; 4]>>) {
        if !self.is_normal_mapped() {
            self.tangents.clear();
            return;
        }
        let given = given.filter(|g| g.len() == self.vertices.len());
        let mut tangents = given.unwrap_or_else(|| vec![[0.0; 4]; self.vertices.len()]);
        if tangents.iter().any(|t| t[3] == 0.0) {
            let mut mikk = Mikk { model: self, tangents: &mut tangents };
            // It fails only without faces; a triangle it cannot frame keeps w = 0 (the G-buffer
            // then reads the vertex normal there).
            let _ = bevy_mikktspace::generate_tangents(&mut mikk);
        }
        self.tangents = tangents;
    }
}

/// The model's triangles as MikkTSpace sees them. Texture v is turned back to point up the image
/// (the vertices keep it pointing down, as the rows are stored), so the bitangent it gives points
/// up, as normal maps are drawn. Only tangents the file did not give (w = 0) are written.
struct Mikk<'a> {
    model: &'a Model,
    tangents: &'a mut Vec<[f32; 4]>,
}

impl Mikk<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.model.indices[3 * face + vert] as usize
    }
}

impl bevy_mikktspace::Geometry for Mikk<'_> {
    fn num_faces(&self) -> usize {
        self.model.triangle_count()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.model.vertices[self.vertex(face, vert)].position
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.model.vertices[self.vertex(face, vert)].normal
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let [u, v] = self.model.vertices[self.vertex(face, vert)].uv;
        [u, 1.0 - v]
    }

    fn set_tangent(&mut self, space: Option<bevy_mikktspace::TangentSpace>, face: usize, vert: usize) {
        let Some(space) = space else { return };
        let tangent = space.tangent_encoded();
        let i = self.vertex(face, vert);
        if self.tangents[i][3] == 0.0 && tangent.iter().all(|x| x.is_finite()) {
            // MikkTSpace's sign is +1 or -1; a zero w would read as "none given".
            let w = if tangent[3] < 0.0 { -1.0 } else { 1.0 };
            self.tangents[i] = [tangent[0], tangent[1], tangent[2], w];
        }
    }
}
